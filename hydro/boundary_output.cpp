#include "hydro/boundary_output.hpp"

#include <cmath>
#include <cstdio>

#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam::hydro {

BoundaryOutput::BoundaryOutput(const BoundaryOutputDef& def, const Grid& grid, const cf::GridMapping& crs,
                               const std::map<std::string, std::string>& attributes)
    : def_(def) {
    const auto& b = def.box;
    const std::string box = number_text(b[0]) + "," + number_text(b[1]) + "," + number_text(b[2]) + "," + number_text(b[3]);
    if (!(b[1] > b[0] && b[3] > b[2])) fail("", "--boundary-box", box + ": needs x_min < x_max and y_min < y_max");
    const double tol = 1e-9 * std::max(grid.dx, grid.dy);
    if (b[0] < grid.x_min_edge() - tol || b[1] > grid.x_max_edge() + tol || b[2] < grid.y_min_edge() - tol ||
        b[3] > grid.y_max_edge() + tol)
        fail("", "--boundary-box",
             box + " reaches outside the grid (x " + number_text(grid.x_min_edge()) + " .. " + number_text(grid.x_max_edge()) +
                 ", y " + number_text(grid.y_min_edge()) + " .. " + number_text(grid.y_max_edge()) + ")");
    check_range("--boundary-interval", def.interval, Range::at_least(0.0, "s"));
    BoundaryFileDef fd;
    auto edge = [&](const char* name, double xa, double ya, double xb, double yb, double spacing) {
        const int n = std::max(1, int(std::lround(std::hypot(xb - xa, yb - ya) / spacing)));
        for (int k = 0; k <= n; ++k) {
            const double s = double(k) / n, x = xa + s * (xb - xa), y = ya + s * (yb - ya);
            char label[32];
            std::snprintf(label, sizeof label, "%s_%04d", name, k);
            fd.x.push_back(x);
            fd.y.push_back(y);
            fd.names.push_back(label);
            stencils_.push_back(point_stencil(grid, x, y));
        }
    };
    edge("west", b[0], b[2], b[0], b[3], grid.dy);
    edge("east", b[1], b[2], b[1], b[3], grid.dy);
    edge("south", b[0], b[2], b[1], b[2], grid.dx);
    edge("north", b[0], b[3], b[1], b[3], grid.dx);
    fd.attributes = attributes;
    fd.attributes["boundary_box"] = box;
    fd.attributes["sample_interval_s"] = def.interval > 0.0 ? number_text(def.interval) : "every step";
    fd.crs = crs;
    file_ = std::make_unique<AtomicOutput>(def.file);
    writer_.emplace(file_->temp_path(), fd);
}

void BoundaryOutput::record(double t0, const std::vector<PointSample>& a, double t1, const std::vector<PointSample>& b) {
    auto add = [&](double ts, double w) {
        time_.push_back(ts);
        for (std::size_t p = 0; p < a.size(); ++p) {
            eta_.push_back((1 - w) * a[p].eta + w * b[p].eta);
            depth_.push_back((1 - w) * a[p].h + w * b[p].h);
            u_.push_back((1 - w) * a[p].u + w * b[p].u);
            v_.push_back((1 - w) * a[p].v + w * b[p].v);
        }
    };
    if (def_.interval <= 0.0) {
        add(t1, 1.0);
        return;
    }
    for (;; ++next_) {
        const double ts = double(next_) * def_.interval;
        if (ts > t1 + 1e-12) break;
        if (ts >= t0 - 1e-12) add(ts, t1 > t0 ? std::clamp((ts - t0) / (t1 - t0), 0.0, 1.0) : 1.0);
    }
}

void BoundaryOutput::flush() {
    writer_->write(flushed_, time_.size(), time_, eta_, depth_, u_, v_);
    flushed_ += time_.size();
    for (auto* v : {&time_, &eta_, &depth_, &u_, &v_}) v->clear();
}

void BoundaryOutput::commit() {
    flush();
    writer_->close();
    file_->commit();
}

}  // namespace flotsam::hydro
