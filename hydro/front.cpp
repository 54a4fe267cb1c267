#include "hydro/front.hpp"

#include <algorithm>
#include <array>

namespace flotsam::hydro {

FrontTracker::FrontTracker(int nx, int ny, double dx, double dy, double g, double dry_depth)
    : nx_(nx), ny_(ny), stride_(std::size_t(nx + 4)), dx_(dx), dy_(dy), g_(g), dry_(dry_depth) {
    tips_.resize(std::size_t(ny));
    y_exchange_.assign(stride_ * std::size_t(ny + 4), 0.0);
    y_any_.assign(std::size_t(ny), 0);
    changed_.resize(std::size_t(ny));
}

void FrontTracker::reset(const std::vector<double>& h, std::vector<double>& alpha) const {
    alpha.resize(h.size());
    for (std::size_t p = 0; p < h.size(); ++p) alpha[p] = h[p] > dry_ ? 1.0 : 0.0;
}

void FrontTracker::fill_ghosts(const std::vector<double>& h, std::vector<double>& alpha, const std::array<bool, 4>& mirror) const {
    // A wall's ghost mirrors the cell inside it, so a tip beside a wall is never fed by
    // its own mirror image (its back face would be the wall, and mass would cross it).
    auto set = [&](int i, int j, int i_in, int j_in, bool mirrored) {
        alpha[at(i, j)] = mirrored ? alpha[at(i_in, j_in)] : (h[at(i, j)] > dry_ ? 1.0 : 0.0);
    };
    for (int j = 0; j < ny_; ++j)
        for (int g = 1; g <= 2; ++g) {
            set(-g, j, g - 1, j, mirror[0]);
            set(nx_ - 1 + g, j, nx_ - g, j, mirror[1]);
        }
    for (int i = 0; i < nx_; ++i)
        for (int g = 1; g <= 2; ++g) {
            set(i, -g, i, g - 1, mirror[2]);
            set(i, ny_ - 1 + g, i, ny_ - g, mirror[3]);
        }
}

void FrontTracker::find_tips(const std::vector<double>& h, const std::vector<double>& hu, const std::vector<double>& hv,
                             const std::vector<double>& alpha, const std::vector<double>& z, const std::vector<double>& g_n2,
                             const std::vector<ColumnRange>& cols) {
    const double dry = dry_;
    bool any = false;
    // A cell is a tip in a direction where the water behind it is wet and full, the
    // ground ahead dry, and it is not full itself; a dry, empty cell only once the level
    // behind stands above its ground (so a shoreline at rest never starts one).
    const std::ptrdiff_t st = std::ptrdiff_t(stride_);
#pragma omp parallel reduction(|| : any)
    {
        std::vector<unsigned char> candidate;
#pragma omp for schedule(static)
        for (int j = 0; j < ny_; ++j) {
            std::vector<Tip>& row = tips_[std::size_t(j)];
            row.clear();
            const ColumnRange c = cols[std::size_t(j)];
            if (c.empty()) continue;
            // Candidates first, in a pass that vectorises: not full, and a wet neighbour,
            // whose level stands above this cell's ground unless this cell holds water or
            // a fraction (the conditions of `behind` below, weakened): the buildings
            // beside the water drop out here.
            candidate.assign(std::size_t(c.end - c.begin), 0);
            const double* hc = h.data() + at(0, j);
            const double* zc = z.data() + at(0, j);
            const double* ac = alpha.data() + at(0, j);
            unsigned char* cand = candidate.data() - c.begin;
#pragma omp simd
            for (int i = c.begin; i < c.end; ++i) {
                const bool wet_w = hc[i - 1] > dry, wet_e = hc[i + 1] > dry, wet_s = hc[i - st] > dry, wet_n = hc[i + st] > dry;
                const bool above =
                    (wet_w & (hc[i - 1] + zc[i - 1] - zc[i] > dry)) | (wet_e & (hc[i + 1] + zc[i + 1] - zc[i] > dry)) |
                    (wet_s & (hc[i - st] + zc[i - st] - zc[i] > dry)) | (wet_n & (hc[i + st] + zc[i + st] - zc[i] > dry));
                const bool holds = (hc[i] > dry) | (ac[i] > 0.0);
                cand[i] = (ac[i] < 1.0) & ((holds & (wet_w | wet_e | wet_s | wet_n)) | above);
            }
            for (int i = c.begin; i < c.end; ++i) {
                if (!cand[i]) continue;
                const std::size_t p = at(i, j);
                const double a = alpha[p];
                const bool wet_here = h[p] > dry || a > 0.0;
                auto behind = [&](std::size_t q) {  // wet and full, and (for an empty cell) above the ground here
                    return h[q] > dry && alpha[q] >= 1.0 && (wet_here || h[q] + z[q] - std::max(z[q], z[p]) > dry);
                };
                // One tip per cell, along the direction the front fills it fastest: a cell fed
                // from two sides holds one wet fraction, which cannot be two wedges at once
                // (the slower wedge's face could then drain an empty cell).
                bool found = false;
                Tip best;
                auto consider = [&](std::size_t up, double u_up, double d, TipDir dir) {
                    const TipInput in{h[up], u_up, z[up], h[p], a, z[p], d, g_n2[p]};
                    const TipFace f = tip_face(in, g_, dry);
                    if (!found || f.alpha_rate > best.face.alpha_rate) best = Tip{i, dir, f};
                    found = true;
                };
                const std::size_t w = p - 1, e = p + 1, s = p - stride_, n = p + stride_;
                const bool dry_w = !(h[w] > dry), dry_e = !(h[e] > dry), dry_s = !(h[s] > dry), dry_n = !(h[n] > dry);
                if (dry_e && behind(w))
                    consider(w, velocity(h[w], hu[w], dry), dx_, TipDir::east);
                else if (dry_w && behind(e))
                    consider(e, -velocity(h[e], hu[e], dry), dx_, TipDir::west);
                if (dry_n && behind(s))
                    consider(s, velocity(h[s], hv[s], dry), dy_, TipDir::north);
                else if (dry_s && behind(n))
                    consider(n, -velocity(h[n], hv[n], dry), dy_, TipDir::south);
                // A front that the bed or friction has stopped (R+ + D <= 0) is no tip: the
                // plain scheme lets that water settle or run back.
                if (found && best.face.alpha_rate > 0.0) row.push_back(best);
            }
            any = any || !row.empty();
        }
    }
    any_ = any;
}

void FrontTracker::grow(const std::vector<double>& alpha_in, double dt, std::vector<double>& alpha_out) const {
    alpha_out = alpha_in;
    if (any_) {
        // Serial, in row order: what overflows one cell may start the next, whichever
        // thread count.
        for (int j = 0; j < ny_; ++j) {
            const std::vector<Tip>& row = tips_[std::size_t(j)];
            for (const Tip& t : row) {
                const std::size_t p = at(t.i, j);
                alpha_out[p] += dt * t.face.alpha_rate;
                const double over = alpha_out[p] - 1.0;
                if (over > 0.0) {
                    const std::size_t next = t.dir == TipDir::east    ? p + 1
                                             : t.dir == TipDir::west  ? p - 1
                                             : t.dir == TipDir::north ? p + stride_
                                                                      : p - stride_;
                    alpha_out[p] = 1.0;
                    alpha_out[next] = std::max(alpha_out[next], 0.0) + over;
                }
            }
        }
    }
}

void FrontTracker::fix(const std::vector<double>& h, const std::vector<ColumnRange>& cols, std::vector<double>& alpha) const {
    const double dry = dry_;
    const std::ptrdiff_t st = std::ptrdiff_t(stride_);
#pragma omp parallel for schedule(static)
    for (int j = 0; j < ny_; ++j) {
        const ColumnRange c = cols[std::size_t(j)];
        const double* hc = h.data() + at(0, j);
        double* ac = alpha.data() + at(0, j);
        // Branch-free, so that it vectorises: it runs over every computed cell, twice a step.
#pragma omp simd
        for (int i = c.begin; i < c.end; ++i) {
            const double hw = hc[i - 1], he = hc[i + 1], hs = hc[i - st], hn = hc[i + st], here = hc[i];
            const bool all_wet = (hw > dry) & (he > dry) & (hs > dry) & (hn > dry);
            const bool any_wet = (hw > dry) | (he > dry) | (hs > dry) | (hn > dry);
            const double deepest = std::max(std::max(hw, he), std::max(hs, hn));
            const double lowest = deepest > here ? here / deepest : 1.0;
            const double a = std::min(ac[i], 1.0);
            const double wet_value = all_wet ? 1.0 : std::max(a, lowest);
            ac[i] = here > dry ? wet_value : (any_wet ? a : 0.0);
        }
    }
}

double FrontTracker::correct_invariants(const std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv,
                                        const std::vector<double>& z, const std::vector<double>& g_n2,
                                        const std::vector<ColumnRange>& cols) {
    const double dry = dry_, g = g_, idx = 1.0 / dx_, idy = 1.0 / dy_;
    const std::ptrdiff_t st = std::ptrdiff_t(stride_);
    double amax = 0.0;
    // A face can exchange only between two wet cells, one less than half as deep as the
    // other: found first in a pass that vectorises (few faces qualify).
    auto thin_beside_thick = [dry](double a, double b) { return (a > dry) & (b > dry) & ((b < 0.5 * a) | (a < 0.5 * b)); };
#pragma omp parallel
    {
        std::vector<double> f;
        std::vector<unsigned char> flag;
        // x faces: each row alone; every exchange of a row from the state before any of them.
#pragma omp for schedule(static)
        for (int j = 0; j < ny_; ++j) {
            std::vector<std::size_t>& changed = changed_[std::size_t(j)];
            changed.clear();
            const ColumnRange c = cols[std::size_t(j)];
            if (c.end - c.begin < 2) continue;
            const double* hc = h.data() + at(0, j);
            flag.assign(std::size_t(c.end - c.begin), 0);
            unsigned char* fl = flag.data() - c.begin;  // fl[i]: the face between columns i and i + 1
#pragma omp simd
            for (int i = c.begin; i < c.end - 1; ++i) fl[i] = thin_beside_thick(hc[i], hc[i + 1]);
            f.assign(std::size_t(c.end - c.begin), 0.0);
            double* F = f.data() - c.begin;
            for (int i = c.begin; i < c.end - 1; ++i) {
                if (!fl[i]) continue;
                const std::size_t l = at(i, j), r = l + 1;
                F[i] = invariant_exchange(h[l], velocity(h[l], hu[l], dry), h[r], velocity(h[r], hu[r], dry), z[r] - z[l],
                                          0.5 * (g_n2[l] + g_n2[r]), dx_, g, dry);
            }
            for (int i = c.begin; i < c.end - 1; ++i) {
                if (F[i] == 0.0) continue;
                hu[at(i, j)] -= F[i];
                hu[at(i + 1, j)] += F[i];
                changed.push_back(at(i, j));
                changed.push_back(at(i + 1, j));
            }
        }
        // y faces: the face below row j (j >= 1), from the state after the x faces. A face
        // row with no candidate is marked and not written (nor read below).
#pragma omp for schedule(static)
        for (int j = 1; j < ny_; ++j) {
            const ColumnRange c = hull(cols[std::size_t(j - 1)], cols[std::size_t(j)]);
            y_any_[std::size_t(j)] = 0;
            if (c.empty()) continue;
            const double* hs = h.data() + at(0, j - 1);
            const double* hn = hs + st;
            flag.assign(std::size_t(c.end - c.begin), 0);
            unsigned char* fl = flag.data() - c.begin;
            bool any = false;
#pragma omp simd reduction(| : any)
            for (int i = c.begin; i < c.end; ++i) {
                fl[i] = thin_beside_thick(hs[i], hn[i]);
                any = any | bool(fl[i]);
            }
            if (!any) continue;
            double* F = y_exchange_.data() + at(0, j);
            std::fill(F + c.begin, F + c.end, 0.0);
            for (int i = c.begin; i < c.end; ++i) {
                if (!fl[i]) continue;
                const std::size_t s = at(i, j - 1), n = at(i, j);
                F[i] = invariant_exchange(h[s], velocity(h[s], hv[s], dry), h[n], velocity(h[n], hv[n], dry), z[n] - z[s],
                                          0.5 * (g_n2[s] + g_n2[n]), dy_, g, dry);
            }
            y_any_[std::size_t(j)] = 1;
        }
#pragma omp for schedule(static)
        for (int j = 0; j < ny_; ++j) {
            const bool has_below = j >= 1 && y_any_[std::size_t(j)], has_above = j + 1 < ny_ && y_any_[std::size_t(j) + 1];
            if (!has_below && !has_above) continue;
            std::vector<std::size_t>& changed = changed_[std::size_t(j)];
            const ColumnRange c = cols[std::size_t(j)];  // within both faces' columns
            const double* below = y_exchange_.data() + at(0, j);
            const double* above = below + st;
            double* q = hv.data() + at(0, j);
            for (int i = c.begin; i < c.end; ++i) {
                // moved north: into this row from below, out of it above
                const double in = has_below ? below[i] : 0.0, out = has_above ? above[i] : 0.0;
                if (in == 0.0 && out == 0.0) continue;
                q[i] += in - out;
                changed.push_back(at(i, j));
            }
        }
        // The step's CFL rate must cover the cells changed (thin water sped up).
#pragma omp for schedule(static) reduction(max : amax)
        for (int j = 0; j < ny_; ++j)
            for (std::size_t p : changed_[std::size_t(j)]) amax = std::max(amax, wave_rate(h[p], hu[p], hv[p], g, dry, idx, idy));
    }
    return amax;
}

}  // namespace flotsam::hydro
