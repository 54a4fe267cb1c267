#include "hydro/front.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>

namespace flotsam::hydro {

namespace {
// The first i in [i, end) with the bit set in m[i], else end; eight cells at a time where
// none is (the marked cells are few).
int next_marked(const unsigned char* m, int i, int end, unsigned bit) {
    const std::uint64_t bits = 0x0101010101010101ull * bit;
    for (std::uint64_t w; i + 8 <= end; i += 8) {
        std::memcpy(&w, m + i, sizeof w);
        if (w & bits) break;
    }
    while (i < end && !(m[i] & bit)) ++i;
    return i;
}
}  // namespace

FrontTracker::FrontTracker(int nx, int ny, double dx, double dy, double g, double dry_depth)
    : nx_(nx), ny_(ny), stride_(std::size_t(nx + 4)), dx_(dx), dy_(dy), g_(g), dry_(dry_depth) {
    tips_.resize(std::size_t(ny));
    marks_.assign(stride_ * std::size_t(ny + 4), 0);
    slot_.assign(stride_ * std::size_t(ny + 4), -1);
    growth_.resize(std::size_t(ny + 4));
    row_marks_.assign(std::size_t(ny), 0);
    marked_cols_.assign(std::size_t(ny), ColumnRange{});
    y_exchange_.resize(std::size_t(ny));
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
    // The last fix()'s marks hold on its own state, except beside a ghost (the ghosts are
    // filled again before each stage).
    const bool marked = marked_h_ == h.data() && marked_alpha_ == alpha.data();
#pragma omp parallel reduction(|| : any)
    {
        std::vector<unsigned char> candidate;
#pragma omp for schedule(static)
        for (int j = 0; j < ny_; ++j) {
            std::vector<Tip>& row = tips_[std::size_t(j)];
            row.clear();
            const ColumnRange c = cols[std::size_t(j)];
            if (c.empty()) continue;
            ColumnRange m = marked && j > 0 && j < ny_ - 1 ? marked_cols_[std::size_t(j)] : ColumnRange{};
            m = {std::max({m.begin, c.begin, 1}), std::min({m.end, c.end, nx_ - 1})};
            if (m.empty()) m = {c.begin, c.begin};
            if (m.begin == c.begin && m.end == c.end && !(row_marks_[std::size_t(j)] & kMayBeTip)) continue;
            // Candidates (may_be_tip): the marks where they hold, else a pass that vectorises.
            candidate.assign(std::size_t(c.end - c.begin), 0);
            const double* hc = h.data() + at(0, j);
            const double* zc = z.data() + at(0, j);
            const double* ac = alpha.data() + at(0, j);
            const unsigned char* mk = marks_.data() + at(0, j);
            unsigned char* cand = candidate.data() - c.begin;
            auto compute = [&](int i0, int i1) {
#pragma omp simd
                for (int i = i0; i < i1; ++i)
                    cand[i] = may_be_tip(hc[i], zc[i], ac[i], hc[i - 1], zc[i - 1], hc[i + 1], zc[i + 1], hc[i - st], zc[i - st],
                                         hc[i + st], zc[i + st], dry);
            };
            compute(c.begin, m.begin);
#pragma omp simd
            for (int i = m.begin; i < m.end; ++i) cand[i] = mk[i] & kMayBeTip;
            compute(m.end, c.end);
            for (int i = next_marked(cand, c.begin, c.end, 1); i < c.end; i = next_marked(cand, i + 1, c.end, 1)) {
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

void FrontTracker::grow(const std::vector<double>& alpha_in, double dt) {
    for (auto& row : growth_) row.clear();
    if (!any_) return;
    // Serial, in row order: what overflows one cell may start the next, whichever thread
    // count. Sparse: the cells touched get a slot in `grown` (the values alpha_in would
    // have after the same operations in the same order).
    std::vector<std::pair<std::size_t, double>> grown;
    auto value = [&](std::size_t p) { return slot_[p] >= 0 ? grown[std::size_t(slot_[p])].second : alpha_in[p]; };
    auto set = [&](std::size_t p, double v) {
        if (slot_[p] < 0) {
            slot_[p] = int(grown.size());
            grown.emplace_back(p, v);
        } else {
            grown[std::size_t(slot_[p])].second = v;
        }
    };
    for (int j = 0; j < ny_; ++j)
        for (const Tip& t : tips_[std::size_t(j)]) {
            const std::size_t p = at(t.i, j);
            set(p, value(p) + dt * t.face.alpha_rate);
            const double over = value(p) - 1.0;
            if (over > 0.0) {
                const std::size_t next = t.dir == TipDir::east    ? p + 1
                                         : t.dir == TipDir::west  ? p - 1
                                         : t.dir == TipDir::north ? p + stride_
                                                                  : p - stride_;
                set(p, 1.0);
                set(next, std::max(value(next), 0.0) + over);
            }
        }
    for (auto [p, v] : grown) {
        slot_[p] = -1;
        growth_[p / stride_].emplace_back(int(p % stride_) - 2, v);
    }
}

void FrontTracker::fix(const std::vector<double>& h, const std::vector<double>& z, const std::vector<ColumnRange>& cols,
                       const std::vector<double>& alpha_in, std::vector<double>& alpha_out, bool grown) {
#pragma omp parallel for schedule(static)
    for (int j = 0; j < ny_; ++j) fix_row(h, z, cols, alpha_in, alpha_out, grown, j);
    fix_done(h, cols, alpha_in, alpha_out, grown);
}

void FrontTracker::fix_row(const std::vector<double>& h, const std::vector<double>& z, const std::vector<ColumnRange>& cols,
                           const std::vector<double>& alpha_in, std::vector<double>& alpha_out, bool grown, int j) {
    const double dry = dry_;
    const std::ptrdiff_t st = std::ptrdiff_t(stride_);
    const ColumnRange c = cols[std::size_t(j)];
    const double* hc = h.data() + at(0, j);
    const double* zc = z.data() + at(0, j);
    const double* ain = alpha_in.data() + at(0, j);
    double* aout = alpha_out.data() + at(0, j);
    unsigned char* mk = marks_.data() + at(0, j);
    if (&alpha_in != &alpha_out) {  // the row outside the columns, ghosts included
        const int b = c.empty() ? nx_ + 2 : c.begin, e = c.empty() ? nx_ + 2 : c.end;
        std::copy(ain - 2, ain + b, aout - 2);
        std::copy(ain + e, ain + nx_ + 2, aout + e);
    }
    // The next row's wet fraction is far in memory by now (the sweep ran through a stage's
    // state since it was written): ask for it while this row is fixed.
    if (j + 1 < ny_)
        for (int i = c.begin; i < c.end; i += 8) __builtin_prefetch(ain + stride_ + i);
    // Branch-free, so that it vectorises: it runs over every computed cell, twice a step.
#pragma omp simd
    for (int i = c.begin; i < c.end; ++i)
        aout[i] = consistent_wet_fraction(ain[i], hc[i], hc[i - 1], hc[i + 1], hc[i - st], hc[i + st], dry);
    // The marks, while the row is in cache (one loop with the above does not vectorise).
    auto mark = [&](int i) {
        const double hw = hc[i - 1], he = hc[i + 1], hs = hc[i - st], hn = hc[i + st], here = hc[i];
        const bool tip = may_be_tip(here, zc[i], aout[i], hw, zc[i - 1], he, zc[i + 1], hs, zc[i - st], hn, zc[i + st], dry);
        return int(tip) * kMayBeTip + int(thin_beside_thick(here, he, dry)) * kThinEastFace +
               int(thin_beside_thick(hs, here, dry)) * kThinSouthFace;
    };
    int any = 0;
#pragma omp simd reduction(| : any)
    for (int i = c.begin; i < c.end; ++i) {
        const int m = mark(i);
        mk[i] = static_cast<unsigned char>(m);
        any |= m;
    }
    // The cells the tips grew (grow()): as if alpha_in held their grown values.
    if (grown)
        for (auto [i, a] : growth_[std::size_t(j + 2)]) {
            if (i < c.begin || i >= c.end) {
                aout[i] = a;
                continue;
            }
            aout[i] = consistent_wet_fraction(a, hc[i], hc[i - 1], hc[i + 1], hc[i - st], hc[i + st], dry);
            const int m = mark(i);
            mk[i] = static_cast<unsigned char>(m);
            any |= m;
        }
    row_marks_[std::size_t(j)] = static_cast<unsigned char>(any);
}

void FrontTracker::fix_done(const std::vector<double>& h, const std::vector<ColumnRange>& cols, const std::vector<double>& alpha_in,
                            std::vector<double>& alpha_out, bool grown) {
    if (&alpha_in != &alpha_out)
        for (int j : {-2, -1, ny_, ny_ + 1}) {
            std::copy(alpha_in.begin() + std::ptrdiff_t(at(-2, j)), alpha_in.begin() + std::ptrdiff_t(at(-2, j) + stride_),
                      alpha_out.begin() + std::ptrdiff_t(at(-2, j)));
            if (grown)
                for (auto [i, a] : growth_[std::size_t(j + 2)]) alpha_out[at(i, j)] = a;
        }
    marked_cols_ = cols;
    marked_h_ = h.data();
    marked_alpha_ = alpha_out.data();
}

double FrontTracker::correct_invariants(const std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv,
                                        const std::vector<double>& z, const std::vector<double>& g_n2) {
    const double dry = dry_, g = g_, idx = 1.0 / dx_, idy = 1.0 / dy_;
    const std::vector<ColumnRange>& cols = marked_cols_;
    double amax = 0.0;
    // A face can exchange only between two wet cells, one less than half as deep as the
    // other: fix() marked those (few) faces.
#pragma omp parallel
    {
        std::vector<std::pair<int, double>> moved;
        // x faces: each row alone; every exchange of a row from the state before any of them.
#pragma omp for schedule(static)
        for (int j = 0; j < ny_; ++j) {
            std::vector<std::size_t>& changed = changed_[std::size_t(j)];
            changed.clear();
            const ColumnRange c = cols[std::size_t(j)];
            if (c.end - c.begin < 2 || !(row_marks_[std::size_t(j)] & kThinEastFace)) continue;
            const unsigned char* mk = marks_.data() + at(0, j);
            moved.clear();
            for (int i = next_marked(mk, c.begin, c.end - 1, kThinEastFace); i < c.end - 1;
                 i = next_marked(mk, i + 1, c.end - 1, kThinEastFace)) {
                const std::size_t l = at(i, j), r = l + 1;
                const double F = invariant_exchange(h[l], velocity(h[l], hu[l], dry), h[r], velocity(h[r], hu[r], dry), z[r] - z[l],
                                                    0.5 * (g_n2[l] + g_n2[r]), dx_, g, dry);
                if (F != 0.0) moved.emplace_back(i, F);
            }
            for (auto [i, F] : moved) {
                hu[at(i, j)] -= F;
                hu[at(i + 1, j)] += F;
                changed.push_back(at(i, j));
                changed.push_back(at(i + 1, j));
            }
        }
        // y faces: the face below row j (j >= 1), from the state after the x faces. Row j
        // is dry outside its columns, so its faces there exchange nothing.
#pragma omp for schedule(static)
        for (int j = 1; j < ny_; ++j) {
            std::vector<std::pair<int, double>>& list = y_exchange_[std::size_t(j)];
            list.clear();
            const ColumnRange c = cols[std::size_t(j)];
            if (!(row_marks_[std::size_t(j)] & kThinSouthFace)) continue;
            const unsigned char* mk = marks_.data() + at(0, j);
            for (int i = next_marked(mk, c.begin, c.end, kThinSouthFace); i < c.end; i = next_marked(mk, i + 1, c.end, kThinSouthFace)) {
                const std::size_t s = at(i, j - 1), n = at(i, j);
                const double F = invariant_exchange(h[s], velocity(h[s], hv[s], dry), h[n], velocity(h[n], hv[n], dry), z[n] - z[s],
                                                    0.5 * (g_n2[s] + g_n2[n]), dy_, g, dry);
                if (F != 0.0) list.emplace_back(i, F);
            }
        }
#pragma omp for schedule(static)
        for (int j = 0; j < ny_; ++j) {
            // moved north: into this row from below, out of it above
            static const std::vector<std::pair<int, double>> none;
            const std::vector<std::pair<int, double>>& below = j >= 1 ? y_exchange_[std::size_t(j)] : none;
            const std::vector<std::pair<int, double>>& above = j + 1 < ny_ ? y_exchange_[std::size_t(j) + 1] : none;
            std::vector<std::size_t>& changed = changed_[std::size_t(j)];
            double* q = hv.data() + at(0, j);
            auto b = below.begin(), a = above.begin();
            while (b != below.end() || a != above.end()) {
                const int i = b == below.end() ? a->first : a == above.end() ? b->first : std::min(a->first, b->first);
                const double in = b != below.end() && b->first == i ? (b++)->second : 0.0;
                const double out = a != above.end() && a->first == i ? (a++)->second : 0.0;
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
