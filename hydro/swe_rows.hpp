// The row kernels of Heun's stage (heun_stage.cpp drives them): each computes one
// quantity along one grid row, from row pointers at padded column 0, over the interior
// columns it is given. Templates on the arithmetic type, the solver's state type
// (BasicSolver<float> or <double>).
#pragma once
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "hydro/column_range.hpp"
#include "hydro/front.hpp"
#include "hydro/front_kernels.hpp"
#include "hydro/solver.hpp"
#include "hydro/swe_kernels.hpp"

namespace flotsam::hydro::rows {

// The row functions below are called once per row and kept out of line (noinline):
// inlined into the stage's OpenMP region, GCC 12 stops vectorising some of them.

// Constants of one stage.
template <class Real>
struct Sweep {
    Real g, dry, theta, order_weight, idx, idy;
    int nx;
};

// Row buffers of one thread, each row `stride` Reals laid out like a grid row.
template <class Real>
class RowBuffers {
public:
    static constexpr int kPrimRows = 5, kSlopeRows = 3, kFaceRows = 2;
    static constexpr std::size_t kRows = 3 * kPrimRows + 4 * kSlopeRows + 4 * kFaceRows + 8 + 3;
    RowBuffers(Real* data, std::size_t stride) : data_(data), stride_(stride) {}
    // Rings indexed by padded row r: primitives (0 eta, 1 u, 2 v); limited y-slopes
    // (0 eta, 1 h, 2 u, 3 v); fluxes through the y-face below row r (0 mass, 1 normal
    // momentum for the cell below, 2 for the cell above, 3 tangential momentum).
    Real* prim(int r, int k) const { return row(k * kPrimRows + r % kPrimRows); }
    Real* slope(int r, int k) const { return row(3 * kPrimRows + k * kSlopeRows + r % kSlopeRows); }
    Real* face(int r, int k) const { return row(3 * kPrimRows + 4 * kSlopeRows + k * kFaceRows + r % kFaceRows); }
    // Scratch of the x-sweep: 0..3 x-slopes of eta, h, u, v; 4..7 x-face fluxes.
    Real* x_work(int k) const { return row(3 * kPrimRows + 4 * kSlopeRows + 4 * kFaceRows + k); }
    // Rates of change of h, hu, hv of the row being updated.
    Real* rate(int k) const { return row(3 * kPrimRows + 4 * kSlopeRows + 4 * kFaceRows + 8 + k); }

private:
    Real* row(int k) const { return data_ + std::size_t(k) * stride_; }
    Real* data_;
    std::size_t stride_;
};

// Row pointers below point at padded column 0 of their row; ranges are interior columns.

// eta = h + z, and velocities (zero where dry).
template <class Real>
[[gnu::noinline]] void primitives_row(const Sweep<Real>& s, ColumnRange cols, const Real* h, const Real* hu, const Real* hv,
                                      const Real* z, Real* __restrict eta, Real* __restrict u, Real* __restrict v) {
#pragma omp simd
    for (int c = cols.begin + kGhost; c < cols.end + kGhost; ++c) {
        eta[c] = h[c] + z[c];
        const Real inv = inverse_depth(h[c], s.dry);
        u[c] = hu[c] * inv;
        v[c] = hv[c] * inv;
    }
}

// Limited y-slopes of one row from the rows below (m), at (0) and above (p); zero
// (first order) where the surface does not span the three (keeps_slope). Order 1: zero
// everywhere.
template <class Real>
[[gnu::noinline]] void y_slopes_row(const Sweep<Real>& s, ColumnRange cols, const Real* hm, const Real* h0, const Real* hp,
                                    const RowBuffers<Real>& w, int r) {
    Real* __restrict se = w.slope(r, 0);
    Real* __restrict sh = w.slope(r, 1);
    Real* __restrict su = w.slope(r, 2);
    Real* __restrict sv = w.slope(r, 3);
    const int c0 = cols.begin + kGhost, c1 = cols.end + kGhost;
    if (s.order_weight == Real(0)) {
        if (c0 < c1)
            for (Real* a : {se, sh, su, sv}) std::fill(a + c0, a + c1, Real(0));
        return;
    }
    const Real *em = w.prim(r - 1, 0), *e0 = w.prim(r, 0), *ep = w.prim(r + 1, 0);
    const Real *um = w.prim(r - 1, 1), *u0 = w.prim(r, 1), *up = w.prim(r + 1, 1);
    const Real *vm = w.prim(r - 1, 2), *v0 = w.prim(r, 2), *vp = w.prim(r + 1, 2);
#pragma omp simd
    for (int c = c0; c < c1; ++c) {
        const Real slope_e = limited_slope(e0[c] - em[c], ep[c] - e0[c], s.theta);
        const Real slope_h = limited_slope(h0[c] - hm[c], hp[c] - h0[c], s.theta);
        const Real wt = keeps_slope(hm[c], em[c], h0[c], e0[c], hp[c], ep[c], slope_e, slope_h, s.dry) ? Real(1) : Real(0);
        se[c] = wt * slope_e;
        sh[c] = wt * slope_h;
        su[c] = wt * limited_slope(u0[c] - um[c], up[c] - u0[c], s.theta);
        sv[c] = wt * limited_slope(v0[c] - vm[c], vp[c] - v0[c], s.theta);
    }
}

// Fluxes through the y-faces between padded rows r-1 (depth hm) and r (depth h0).
template <class Real>
[[gnu::noinline]] void y_faces_row(const Sweep<Real>& s, ColumnRange cols, const Real* hm, const Real* h0,
                                   const RowBuffers<Real>& w, int r) {
    const Real *em = w.prim(r - 1, 0), *e0 = w.prim(r, 0);
    const Real *um = w.prim(r - 1, 1), *u0 = w.prim(r, 1);
    const Real *vm = w.prim(r - 1, 2), *v0 = w.prim(r, 2);
    const Real *sem = w.slope(r - 1, 0), *se0 = w.slope(r, 0), *shm = w.slope(r - 1, 1), *sh0 = w.slope(r, 1);
    const Real *sum = w.slope(r - 1, 2), *su0 = w.slope(r, 2), *svm = w.slope(r - 1, 3), *sv0 = w.slope(r, 3);
    Real* __restrict mass = w.face(r, 0);
    Real* __restrict lo = w.face(r, 1);
    Real* __restrict hi = w.face(r, 2);
    Real* __restrict tan = w.face(r, 3);
#pragma omp simd
    for (int c = cols.begin + kGhost; c < cols.end + kGhost; ++c) {
        FaceFluxOf<Real> f;
        face_flux(em[c] + Real(0.5) * sem[c], hm[c] + Real(0.5) * shm[c], vm[c] + Real(0.5) * svm[c], um[c] + Real(0.5) * sum[c],
                  e0[c] - Real(0.5) * se0[c], h0[c] - Real(0.5) * sh0[c], v0[c] - Real(0.5) * sv0[c], u0[c] - Real(0.5) * su0[c],
                  s.g, s.dry, f);
        mass[c] = f.mass;
        lo[c] = f.normal_L;
        hi[c] = f.normal_R;
        tan[c] = f.tangential;
    }
}

// ---- Fronts (front.hpp): the sweep's changes at tip cells ----
// A tip cell and its neighbours along the front's direction are first order (slopes
// zero); its back face takes the wedge's state, its face toward the dry side is shut.
inline bool is_x(TipDir d) { return d == TipDir::east || d == TipDir::west; }

// Zero the x-slopes of a row's x-tips and their x-neighbours, in padded columns [c0, c1);
// an edge cell's ghost too, so that a wall's mirror image stays a mirror image (else the
// wall face's two states differ and water crosses it).
template <class Real>
void x_slopes_at_tips(const std::vector<Tip>& tips, int nx, int c0, int c1, Real* se, Real* sh, Real* su, Real* sv) {
    for (const Tip& t : tips) {
        if (!is_x(t.dir)) continue;
        int lo = t.i + kGhost - 1, hi = t.i + kGhost + 1;
        if (lo == kGhost) --lo;
        if (hi == nx - 1 + kGhost) ++hi;
        for (int c = std::max(lo, c0); c <= std::min(hi, c1 - 1); ++c) se[c] = sh[c] = su[c] = sv[c] = 0.0;
    }
}

// Flux through a tip's back face from the wedge state (n: +1 when the front moves toward
// +x or +y, the tip on the face's high side), tangential velocities ut_lo, ut_hi.
// Tips are computed in double whatever Real is: their state (TipFace) is double.
template <class Real>
FaceFlux back_face_flux(const Sweep<Real>& s, const TipFace& f, double n, double ut_lo, double ut_hi) {
    FaceFlux out;
    if (n > 0.0)
        face_flux(f.eta_up, f.h_up, f.u, ut_lo, f.eta_tip, f.h_tip, f.u, ut_hi, double(s.g), double(s.dry), out);
    else
        face_flux(f.eta_tip, f.h_tip, -f.u, ut_lo, f.eta_up, f.h_up, -f.u, ut_hi, double(s.g), double(s.dry), out);
    return out;
}

template <class Real>
void store(const FaceFlux& f, int c, Real* fm, Real* fl, Real* fr, Real* ft) {
    fm[c] = f.mass;
    fl[c] = f.normal_L;
    fr[c] = f.normal_R;
    ft[c] = f.tangential;
}

// The x faces of a row's x-tips (face c between padded columns c and c+1; cell values,
// since the slopes there are zero).
template <class Real>
void x_faces_at_tips(const Sweep<Real>& s, const std::vector<Tip>& tips, const Real* e, const Real* h, const Real* v, Real* fm,
                     Real* fl, Real* fr, Real* ft) {
    for (const Tip& t : tips) {
        if (!is_x(t.dir)) continue;
        const int c = t.i + kGhost;
        const bool east = t.dir == TipDir::east;
        const int back = east ? c - 1 : c, shut = east ? c : c - 1;
        store(back_face_flux(s, t.face, east ? 1.0 : -1.0, v[back], v[back + 1]), back, fm, fl, fr, ft);
        FaceFlux f;
        shut_face_flux(e[shut], h[shut], e[shut + 1], h[shut + 1], s.g, f);
        store(f, shut, fm, fl, fr, ft);
    }
}

// Rates of change of the cells `cols` of padded row r: the x-direction (slopes, face
// fluxes, bed slope; branch-free so it vectorises), then the y-faces below and above
// and the y bed slope. Returns the mass fluxes through the west and east boundary faces.
template <class Real>
[[gnu::noinline]] std::pair<Real, Real> rates_row(const Sweep<Real>& s, ColumnRange cols, const Real* h, const RowBuffers<Real>& w,
                                                  int r, const std::vector<Tip>* tips) {
    const Real* __restrict e = w.prim(r, 0);
    const Real* __restrict u = w.prim(r, 1);
    const Real* __restrict v = w.prim(r, 2);
    Real* __restrict se = w.x_work(0);
    Real* __restrict sh = w.x_work(1);
    Real* __restrict su = w.x_work(2);
    Real* __restrict sv = w.x_work(3);
    Real* __restrict fm = w.x_work(4);
    Real* __restrict fl = w.x_work(5);
    Real* __restrict fr = w.x_work(6);
    Real* __restrict ft = w.x_work(7);
    Real* __restrict dh = w.rate(0);
    Real* __restrict dhu = w.rate(1);
    Real* __restrict dhv = w.rate(2);
    const int c0 = cols.begin + kGhost, c1 = cols.end + kGhost;  // cells; faces c0-1 .. c1-1
// Slopes on the cells beside the faces; zero (first order) next to a dry cell, which
// keeps h >= 0 and the shoreline at rest, and where the ground cuts the surface
// (keeps_slope). Order 1: the weight is zero everywhere.
#pragma omp simd
    for (int c = c0 - 1; c < c1 + 1; ++c) {
        const Real slope_e = limited_slope(e[c] - e[c - 1], e[c + 1] - e[c], s.theta);
        const Real slope_h = limited_slope(h[c] - h[c - 1], h[c + 1] - h[c], s.theta);
        const bool keep = keeps_slope(h[c - 1], e[c - 1], h[c], e[c], h[c + 1], e[c + 1], slope_e, slope_h, s.dry);
        const Real wt = keep ? s.order_weight : Real(0);
        se[c] = wt * slope_e;
        sh[c] = wt * slope_h;
        su[c] = wt * limited_slope(u[c] - u[c - 1], u[c + 1] - u[c], s.theta);
        sv[c] = wt * limited_slope(v[c] - v[c - 1], v[c + 1] - v[c], s.theta);
    }
    if (tips) x_slopes_at_tips(*tips, s.nx, c0 - 1, c1 + 1, se, sh, su, sv);
// Face c+1/2 between padded columns c and c+1.
#pragma omp simd
    for (int c = c0 - 1; c < c1; ++c) {
        FaceFluxOf<Real> f;
        face_flux(e[c] + Real(0.5) * se[c], h[c] + Real(0.5) * sh[c], u[c] + Real(0.5) * su[c], v[c] + Real(0.5) * sv[c],
                  e[c + 1] - Real(0.5) * se[c + 1], h[c + 1] - Real(0.5) * sh[c + 1], u[c + 1] - Real(0.5) * su[c + 1],
                  v[c + 1] - Real(0.5) * sv[c + 1], s.g, s.dry, f);
        fm[c] = f.mass;
        fl[c] = f.normal_L;
        fr[c] = f.normal_R;
        ft[c] = f.tangential;
    }
    if (tips) x_faces_at_tips(s, *tips, e, h, v, fm, fl, fr, ft);
#pragma omp simd
    for (int c = c0; c < c1; ++c) {
        const Real hw = h[c] - Real(0.5) * sh[c], he = h[c] + Real(0.5) * sh[c];
        const Real zw = e[c] - Real(0.5) * se[c] - hw, ze = e[c] + Real(0.5) * se[c] - he;
        dh[c] = -(fm[c] - fm[c - 1]) * s.idx;
        dhu[c] = -(fl[c] - fr[c - 1]) * s.idx - s.g * Real(0.5) * (hw + he) * (ze - zw) * s.idx;
        dhv[c] = -(ft[c] - ft[c - 1]) * s.idx;
    }
    const Real *sye = w.slope(r, 0), *syh = w.slope(r, 1);
    const Real *gm = w.face(r, 0), *gm_n = w.face(r + 1, 0), *glo_n = w.face(r + 1, 1), *ghi = w.face(r, 2);
    const Real *gt = w.face(r, 3), *gt_n = w.face(r + 1, 3);
#pragma omp simd
    for (int c = c0; c < c1; ++c) {
        const Real hs = h[c] - Real(0.5) * syh[c], hn = h[c] + Real(0.5) * syh[c];
        const Real zs = e[c] - Real(0.5) * sye[c] - hs, zn = e[c] + Real(0.5) * sye[c] - hn;
        dh[c] -= (gm_n[c] - gm[c]) * s.idy;
        dhv[c] -= (glo_n[c] - ghi[c]) * s.idy + s.g * Real(0.5) * (hs + hn) * (zn - zs) * s.idy;
        dhu[c] -= (gt_n[c] - gt[c]) * s.idy;
    }
    return {cols.begin == 0 ? fm[1] : Real(0), cols.end == s.nx ? fm[s.nx + 1] : Real(0)};
}

// out = a * base + (1 - a) * friction(in + dt * rate) on the cells `cols` of a row;
// without a base (predictor), out = friction(in + dt * rate). `base` may be `out`: each
// cell reads its base value before writing it. Counts round-off negative depths.
template <class Real, bool kWithBase, Friction kFriction>
[[gnu::noinline]] void update_row(const Sweep<Real>& s, ColumnRange cols, Real dt, Real a, const Real* h, const Real* hu,
                                  const Real* hv, const RowBuffers<Real>& w, const Real* g_n2, const Real* h0, const Real* hu0,
                                  const Real* hv0, Real* h_out, Real* hu_out, Real* hv_out, long& fixes_total, Real& worst_total) {
    const Real *dh = w.rate(0), *dhu = w.rate(1), *dhv = w.rate(2);
    const Real dry_depth = s.dry;
    long fixes = 0;
    Real worst = 0;
#pragma omp simd reduction(+ : fixes) reduction(min : worst)
    for (int c = cols.begin + kGhost; c < cols.end + kGhost; ++c) {
        Real hn = h[c] + dt * dh[c];
        Real qx = hu[c] + dt * dhu[c];
        Real qy = hv[c] + dt * dhv[c];
        // Negative only by round-off under the CFL bound; counted, then removed.
        const bool negative = hn < Real(0);
        worst = std::min(worst, hn);
        fixes += negative ? 1 : 0;
        hn = negative ? Real(0) : hn;
        if constexpr (kFriction == Friction::explicit_) {  // study only: forward Euler on the old state
            const Real e = explicit_friction_rate(h[c], hu[c], hv[c], g_n2[c], dt, dry_depth);
            qx -= e * hu[c];
            qy -= e * hv[c];
        } else {
            const Real r = friction_factor(hn, qx, qy, g_n2[c], dt, dry_depth);
            qx *= r;
            qy *= r;
        }
        if constexpr (kWithBase) {
            hn = a * h0[c] + (Real(1) - a) * hn;
            qx = a * hu0[c] + (Real(1) - a) * qx;
            qy = a * hv0[c] + (Real(1) - a) * qy;
        }
        // Thin layers keep their momentum (their velocity is desingularised where it is
        // used, inverse_depth); a cell that holds no water holds none (+0, so that
        // exactly dry land stays skippable: -0 + 0 = +0). Arithmetic, not a select, so
        // that GCC vectorises the loop (a select after the friction's division does not).
        const Real holds_water = hn > Real(0) ? Real(1) : Real(0);
        qx = qx * holds_water + Real(0);
        qy = qy * holds_water + Real(0);
        h_out[c] = hn;
        hu_out[c] = qx;
        hv_out[c] = qy;
    }
    fixes_total += fixes;
    worst_total = std::min(worst_total, worst);
}

// update_row with the friction treatment chosen at run time.
template <class Real, bool kWithBase, typename... Args>
void update_row_with(Friction friction, Args&&... args) {
    if (friction == Friction::explicit_)
        update_row<Real, kWithBase, Friction::explicit_>(std::forward<Args>(args)...);
    else
        update_row<Real, kWithBase, Friction::implicit>(std::forward<Args>(args)...);
}

// Largest CFL rate of the cells `cols` of a row.
template <class Real>
[[gnu::noinline]] Real max_wave_rate_row(const Sweep<Real>& s, ColumnRange cols, const Real* h, const Real* hu, const Real* hv) {
    Real a = 0;
#pragma omp simd reduction(max : a)
    for (int c = cols.begin + kGhost; c < cols.end + kGhost; ++c)
        a = std::max(a, wave_rate(h[c], hu[c], hv[c], s.g, s.dry, s.idx, s.idy));
    return a;
}

}  // namespace flotsam::hydro::rows
