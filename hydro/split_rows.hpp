// The row kernels of the split step (split_step.cpp drives them): dimensionally split
// MUSCL-Hancock, one sweep along x and one along y per step, their order alternating
// from step to step (Strang's second order over each pair of steps).
//
// Along one direction (x here; y swaps the roles of u and v) the equations are
//
//   h_t + (hu)_x = 0,   (hu)_t + (hu^2 + g h^2/2)_x = -g h z_x,   (hv)_t + (huv)_x = 0,
//
// and in primitive form, with the level eta = h + z,
//
//   h_t + u h_x + h u_x = 0,   u_t + u u_x + g eta_x = 0,   v_t + u v_x = 0.
//
// A sweep over dt: the limited slopes s of eta, h, u, v in each cell (the same limiter
// and the same first-order rules at dry cells and where the ground cuts the surface as
// the unsplit scheme, swe_kernels.hpp); the Hancock predictor takes each cell's values
// half a step on with the primitive form,
//
//   dh = -dt/(2 dx) (u s_h + h s_u),   du = -dt/(2 dx) (u s_u + g s_eta),   dv = -dt/(2 dx) u s_v,
//
// added to eta and h alike (so the bed each face implies, eta - h, does not move: a lake
// at rest, u = 0 and s_eta = 0, has dh = du = 0 and stays exact); the face values are the
// predicted centre values -/+ s/2, the flux the unsplit scheme's (hydrostatic
// reconstruction, HLL, the dry-bed fan) at the half step, and the update is conservative
// with the centred bed term -g h_{n+1/2} (s_eta - s_h)/dx, h_{n+1/2} = h + dh. A cell whose
// predicted face depth would fall below zero keeps its unpredicted values (dh = du = dv =
// 0), which keeps every face depth >= 0. The second sweep of a step ends with the implicit
// Manning friction over the whole dt (swe_kernels.hpp).
//
// Why split: each sweep is one-dimensional, stable up to dt (|u| + c)/dx = 1 along its own
// direction, so the step is cfl / max((|u| + c)/dx, (|v| + c)/dy), where the unsplit
// Heun scheme needs cfl / ((|u| + c)/dx + (|v| + c)/dy): about twice the step where both
// speeds are alike (the gravity waves of still water), with one flux evaluation per
// direction instead of Heun's two. docs/hydro.md gives its cost and error against the
// unsplit scheme.
#pragma once
#include <algorithm>
#include <cstddef>
#include <utility>

#include "hydro/column_range.hpp"
#include "hydro/solver.hpp"
#include "hydro/swe_kernels.hpp"
#include "hydro/swe_rows.hpp"

namespace flotsam::hydro::split {

using rows::Sweep;

// The step's CFL rate of a cell for the split step: the larger of the two directions'.
template <class Real>
inline Real directional_wave_rate(Real h, Real hu, Real hv, Real g, Real dry_depth, Real idx, Real idy) {
    const Real c = sqrt(g * h);
    const Real inv = inverse_depth(h, dry_depth);
    return max((abs(hu) * inv + c) * idx, (abs(hv) * inv + c) * idy);
}

// The cells of one 512-bit vector.
template <class Real>
inline constexpr int kVector = 64 / int(sizeof(Real));

// Calls body(c) for every c0 <= c < c1, a vector's cells at a time, the last block moved
// back to end at c1 (overlapping the block before it) where a scalar remainder would be:
// remainders took a tenth to a quarter of the row kernels' time. So body(c) may run twice
// for a cell: it must write only what it does not read. With `lo` and `hi`, body(c)
// returns two values whose least and greatest over the cells go into them.
template <class Real, class Body>
[[gnu::always_inline]] inline void vector_blocks(int c0, int c1, Body&& body) {
    constexpr int w = kVector<Real>;
    if (c1 - c0 < w) {
#pragma omp simd
        for (int c = c0; c < c1; ++c) body(c);
        return;
    }
    for (int b = c0; b < c1; b += w) {
        const int start = min(b, c1 - w);
#pragma omp simd
        for (int k = 0; k < w; ++k) body(start + k);
    }
}
template <class Real, class Body>
[[gnu::always_inline]] inline void vector_blocks(int c0, int c1, Real& lo, Real& hi, Body&& body) {
    constexpr int w = kVector<Real>;
    Real a = lo, z = hi;
    if (c1 - c0 < w) {
#pragma omp simd reduction(min : a) reduction(max : z)
        for (int c = c0; c < c1; ++c) {
            const std::pair<Real, Real> v = body(c);
            a = min(a, v.first);
            z = max(z, v.second);
        }
    } else {
        for (int b = c0; b < c1; b += w) {
            const int start = min(b, c1 - w);
#pragma omp simd reduction(min : a) reduction(max : z)
            for (int k = 0; k < w; ++k) {
                const std::pair<Real, Real> v = body(start + k);
                a = min(a, v.first);
                z = max(z, v.second);
            }
        }
    }
    lo = a;
    hi = z;
}

// The negative depths an update clamped in the cells [c0, c1) (flags 1 or 0, written by
// update_cell): counted only where the update's least depth was below zero (rare).
template <class Real>
long count_clamped(int c0, int c1, const Real* negative, Real worst) {
    long n = 0;
    for (int c = c0; worst < Real(0) && c < c1; ++c) n += negative[c] != Real(0) ? 1 : 0;
    return n;
}

// Row buffers of one thread for a sweep, each row `stride` Reals laid out like a grid row.
template <class Real>
class Buffers {
public:
    static constexpr int kPrimRows = 5, kSlopeRows = 3, kFaceRows = 2;
    static constexpr int kSlopeVars = 7;  // slopes of eta, h, un, ut; predictor dh, dun, dut
    static constexpr int kXRows = 15;     // the x sweep's scratch (x_work), and the clamped depths of either sweep
    static constexpr std::size_t kRows = 3 * kPrimRows + kSlopeVars * kSlopeRows + 4 * kFaceRows + kXRows;
    Buffers(Real* data, std::size_t stride) : data_(data), stride_(stride) {}
    // Rings of the y sweep indexed by padded row r: primitives (0 eta, 1 u, 2 v); slopes
    // and predictor (0 s_eta, 1 s_h, 2 s_v, 3 s_u, 4 dh, 5 dv, 6 du: normal v first);
    // fluxes through the y face below row r (0 mass, 1 normal momentum for the cell
    // below, 2 for the cell above, 3 tangential momentum).
    Real* prim(int r, int k) const { return row(k * kPrimRows + r % kPrimRows); }
    Real* slope(int r, int k) const { return row(3 * kPrimRows + k * kSlopeRows + r % kSlopeRows); }
    Real* face(int r, int k) const { return row(3 * kPrimRows + kSlopeVars * kSlopeRows + k * kFaceRows + r % kFaceRows); }
    // Scratch of one row of the x sweep: 0..2 eta, u, v; 3..6 slopes of eta, h, u, v;
    // 7..9 predictor dh, du, dv; 10..13 face fluxes (mass, normal left, normal right,
    // tangential).
    Real* x_work(int k) const { return row(3 * kPrimRows + kSlopeVars * kSlopeRows + 4 * kFaceRows + k); }
    // 1 where the row's update clamped a negative depth (update_cell), either sweep.
    Real* clamped() const { return x_work(14); }

private:
    Real* row(int k) const { return data_ + std::size_t(k) * stride_; }
    Real* data_;
    std::size_t stride_;
};

// Slopes and Hancock predictor of one cell along a direction with normal velocity un and
// tangential ut (m before, 0 the cell, p after): the slopes s_eta, s_h, s_un, s_ut and the
// predictor increments dh, dun, dut over half the step. hdt = dt / (2 dx).
template <class Real>
[[gnu::always_inline]] inline void slopes_and_predictor(const Sweep<Real>& s, Real hdt, Real hm, Real em, Real unm, Real utm, Real h0, Real e0, Real un0,
                                 Real ut0, Real hp, Real ep, Real unp, Real utp, Real& se, Real& sh, Real& sun, Real& sut, Real& dh,
                                 Real& dun, Real& dut) {
    const Real slope_e = limited_slope(e0 - em, ep - e0, s.theta);
    const Real slope_h = limited_slope(h0 - hm, hp - h0, s.theta);
    const Real wt = keeps_slope(hm, em, h0, e0, hp, ep, slope_e, slope_h, s.dry) ? s.order_weight : Real(0);
    se = wt * slope_e;
    sh = wt * slope_h;
    sun = wt * limited_slope(un0 - unm, unp - un0, s.theta);
    sut = wt * limited_slope(ut0 - utm, utp - ut0, s.theta);
    const Real ph = -hdt * (un0 * sh + h0 * sun);
    const Real pun = -hdt * (un0 * sun + s.g * se);
    const Real put = -hdt * (un0 * sut);
    // Both predicted face depths h + dh -/+ s_h/2 stay >= 0, or the cell is not predicted.
    const Real keep = h0 + ph - Real(0.5) * abs(sh) >= Real(0) ? Real(1) : Real(0);
    dh = keep * ph;
    dun = keep * pun;
    dut = keep * put;
}

// The update of one cell from its rates: depth and the normal and tangential discharges
// over dt, a round-off negative depth flagged (clamped = 1) and removed, with kFriction
// the implicit friction of the whole step (friction_dt), and no momentum where no water
// (+0, so that dry land stays skippable; arithmetic, not a select, so that the loop
// vectorises). Returns the depth before the clamp.
template <class Real, bool kFriction>
[[gnu::always_inline]] inline Real update_cell(Real dt, Real h, Real qn, Real qt, Real rate_h, Real rate_qn, Real rate_qt, Real g_n2,
                                               Real friction_dt, Real dry, Real& h_out, Real& qn_out, Real& qt_out, Real& clamped) {
    Real hn = h + dt * rate_h;
    Real a = qn + dt * rate_qn;
    Real b = qt + dt * rate_qt;
    const Real unclamped = hn;
    const bool negative = hn < Real(0);
    clamped = negative ? Real(1) : Real(0);
    hn = negative ? Real(0) : hn;
    if constexpr (kFriction) {
        const Real r = friction_factor(hn, a, b, g_n2, friction_dt, dry);
        a *= r;
        b *= r;
    }
    const Real holds_water = hn > Real(0) ? Real(1) : Real(0);
    h_out = hn;
    qn_out = a * holds_water + Real(0);
    qt_out = b * holds_water + Real(0);
    return unclamped;
}

// The x sweep of one row over its columns `cols` (nonempty), from (h, hu, hv) to
// (h_out, hu_out, hv_out); kFriction: the step's second sweep, friction over
// friction_dt; kRate: also the largest CFL rate of the new row, into rate_max. Returns
// the mass fluxes through the west and east boundary faces [m^2/s] (0 unless the row's
// columns reach them).
template <class Real, bool kFriction, bool kRate>
[[gnu::noinline]] std::pair<Real, Real> x_row(const Sweep<Real>& s, ColumnRange cols, Real dt, Real friction_dt, const Real* h,
                                              const Real* hu, const Real* hv, const Real* z, const Real* g_n2,
                                              const Buffers<Real>& w, Real* h_out, Real* hu_out, Real* hv_out, long& fixes_total,
                                              Real& worst_total, Real& rate_max) {
    Real* __restrict e = w.x_work(0);
    Real* __restrict u = w.x_work(1);
    Real* __restrict v = w.x_work(2);
    Real* __restrict se = w.x_work(3);
    Real* __restrict sh = w.x_work(4);
    Real* __restrict su = w.x_work(5);
    Real* __restrict sv = w.x_work(6);
    Real* __restrict ph = w.x_work(7);
    Real* __restrict pu = w.x_work(8);
    Real* __restrict pv = w.x_work(9);
    Real* __restrict fm = w.x_work(10);
    Real* __restrict fl = w.x_work(11);
    Real* __restrict fr = w.x_work(12);
    Real* __restrict ft = w.x_work(13);
    const int c0 = cols.begin + kGhost, c1 = cols.end + kGhost;  // cells; faces c0-1 .. c1-1
    vector_blocks<Real>(c0 - 2, c1 + 2, [&](int c) __attribute__((always_inline)) {
        e[c] = h[c] + z[c];
        const Real inv = inverse_depth(h[c], s.dry);
        u[c] = hu[c] * inv;
        v[c] = hv[c] * inv;
    });
    const Real hdt = Real(0.5) * dt * s.idx;
    vector_blocks<Real>(c0 - 1, c1 + 1, [&](int c) __attribute__((always_inline)) {
        slopes_and_predictor(s, hdt, h[c - 1], e[c - 1], u[c - 1], v[c - 1], h[c], e[c], u[c], v[c], h[c + 1], e[c + 1], u[c + 1],
                             v[c + 1], se[c], sh[c], su[c], sv[c], ph[c], pu[c], pv[c]);
    });
    // Face c+1/2 between padded columns c and c+1, at the half step.
    vector_blocks<Real>(c0 - 1, c1, [&](int c) __attribute__((always_inline)) {
        FaceFluxOf<Real> f;
        const Real hl = h[c] + ph[c], hr = h[c + 1] + ph[c + 1];
        face_flux(e[c] + ph[c] + Real(0.5) * se[c], hl + Real(0.5) * sh[c], u[c] + pu[c] + Real(0.5) * su[c],
                  v[c] + pv[c] + Real(0.5) * sv[c], e[c + 1] + ph[c + 1] - Real(0.5) * se[c + 1], hr - Real(0.5) * sh[c + 1],
                  u[c + 1] + pu[c + 1] - Real(0.5) * su[c + 1], v[c + 1] + pv[c + 1] - Real(0.5) * sv[c + 1], s.g, s.dry, f);
        fm[c] = f.mass;
        fl[c] = f.normal_L;
        fr[c] = f.normal_R;
        ft[c] = f.tangential;
    });
    Real* __restrict clamped = w.clamped();
    Real worst = 0, rate = 0;
    vector_blocks<Real>(c0, c1, worst, rate, [&](int c) __attribute__((always_inline)) {
        const Real rate_h = -(fm[c] - fm[c - 1]) * s.idx;
        // Centred bed term at the half step: -g h (z_e - z_w)/dx, z_e - z_w = s_eta - s_h.
        const Real rate_qx = -(fl[c] - fr[c - 1]) * s.idx - s.g * (h[c] + ph[c]) * (se[c] - sh[c]) * s.idx;
        const Real rate_qy = -(ft[c] - ft[c - 1]) * s.idx;
        const Real depth = update_cell<Real, kFriction>(dt, h[c], hu[c], hv[c], rate_h, rate_qx, rate_qy, g_n2[c], friction_dt, s.dry,
                                                        h_out[c], hu_out[c], hv_out[c], clamped[c]);
        const Real cell_rate = kRate ? directional_wave_rate(h_out[c], hu_out[c], hv_out[c], s.g, s.dry, s.idx, s.idy) : Real(0);
        return std::pair<Real, Real>{depth, cell_rate};
    });
    fixes_total += count_clamped(c0, c1, clamped, worst);
    worst_total = min(worst_total, worst);
    rate_max = max(rate_max, rate);
    return {cols.begin == 0 ? fm[kGhost - 1] : Real(0), cols.end == s.nx ? fm[s.nx + kGhost - 1] : Real(0)};
}

// The y sweep's primitives of padded row r (eta, u, v) over the padded columns [c0, c1).
template <class Real>
[[gnu::noinline]] void y_primitives_row(const Sweep<Real>& s, int c0, int c1, const Real* h, const Real* hu, const Real* hv,
                                        const Real* z, const Buffers<Real>& w, int r) {
    Real* __restrict e = w.prim(r, 0);
    Real* __restrict u = w.prim(r, 1);
    Real* __restrict v = w.prim(r, 2);
    vector_blocks<Real>(c0, c1, [&](int c) __attribute__((always_inline)) {
        e[c] = h[c] + z[c];
        const Real inv = inverse_depth(h[c], s.dry);
        u[c] = hu[c] * inv;
        v[c] = hv[c] * inv;
    });
}

// Slopes along y and the predictor of padded row r from the rows below (hm), at (h0)
// and above (hp), over the padded columns [c0, c1).
template <class Real>
[[gnu::noinline]] void y_slopes_row(const Sweep<Real>& s, int c0, int c1, Real hdt, const Real* hm, const Real* h0, const Real* hp,
                                    const Buffers<Real>& w, int r) {
    const Real *em = w.prim(r - 1, 0), *e0 = w.prim(r, 0), *ep = w.prim(r + 1, 0);
    const Real *um = w.prim(r - 1, 1), *u0 = w.prim(r, 1), *up = w.prim(r + 1, 1);
    const Real *vm = w.prim(r - 1, 2), *v0 = w.prim(r, 2), *vp = w.prim(r + 1, 2);
    Real* __restrict se = w.slope(r, 0);
    Real* __restrict sh = w.slope(r, 1);
    Real* __restrict sv = w.slope(r, 2);
    Real* __restrict su = w.slope(r, 3);
    Real* __restrict ph = w.slope(r, 4);
    Real* __restrict pv = w.slope(r, 5);
    Real* __restrict pu = w.slope(r, 6);
    vector_blocks<Real>(c0, c1, [&](int c) __attribute__((always_inline)) {
        slopes_and_predictor(s, hdt, hm[c], em[c], vm[c], um[c], h0[c], e0[c], v0[c], u0[c], hp[c], ep[c], vp[c], up[c], se[c], sh[c],
                             sv[c], su[c], ph[c], pv[c], pu[c]);
    });
}

// Fluxes through the y faces between padded rows r-1 (depth hm) and r (depth h0), at the
// half step, over the padded columns [c0, c1).
template <class Real>
[[gnu::noinline]] void y_faces_row(const Sweep<Real>& s, int c0, int c1, const Real* hm, const Real* h0, const Buffers<Real>& w,
                                   int r) {
    const Real *em = w.prim(r - 1, 0), *e0 = w.prim(r, 0);
    const Real *um = w.prim(r - 1, 1), *u0 = w.prim(r, 1);
    const Real *vm = w.prim(r - 1, 2), *v0 = w.prim(r, 2);
    const Real *sem = w.slope(r - 1, 0), *se0 = w.slope(r, 0), *shm = w.slope(r - 1, 1), *sh0 = w.slope(r, 1);
    const Real *svm = w.slope(r - 1, 2), *sv0 = w.slope(r, 2), *sum = w.slope(r - 1, 3), *su0 = w.slope(r, 3);
    const Real *phm = w.slope(r - 1, 4), *ph0 = w.slope(r, 4), *pvm = w.slope(r - 1, 5), *pv0 = w.slope(r, 5);
    const Real *pum = w.slope(r - 1, 6), *pu0 = w.slope(r, 6);
    Real* __restrict mass = w.face(r, 0);
    Real* __restrict lo = w.face(r, 1);
    Real* __restrict hi = w.face(r, 2);
    Real* __restrict tan = w.face(r, 3);
    vector_blocks<Real>(c0, c1, [&](int c) __attribute__((always_inline)) {
        FaceFluxOf<Real> f;
        face_flux(em[c] + phm[c] + Real(0.5) * sem[c], hm[c] + phm[c] + Real(0.5) * shm[c], vm[c] + pvm[c] + Real(0.5) * svm[c],
                  um[c] + pum[c] + Real(0.5) * sum[c], e0[c] + ph0[c] - Real(0.5) * se0[c], h0[c] + ph0[c] - Real(0.5) * sh0[c],
                  v0[c] + pv0[c] - Real(0.5) * sv0[c], u0[c] + pu0[c] - Real(0.5) * su0[c], s.g, s.dry, f);
        mass[c] = f.mass;
        lo[c] = f.normal_L;
        hi[c] = f.normal_R;
        tan[c] = f.tangential;
    });
}

// The y sweep's update of padded row r over its columns `cols` (interior; nonempty): from
// (h, hu, hv) to the outputs, with the faces below r and r + 1 in the buffers.
template <class Real, bool kFriction, bool kRate>
[[gnu::noinline]] void y_update_row(const Sweep<Real>& s, ColumnRange cols, Real dt, Real friction_dt, const Real* h,
                                    const Real* hu, const Real* hv, const Real* g_n2, const Buffers<Real>& w, int r, Real* h_out,
                                    Real* hu_out, Real* hv_out, long& fixes_total, Real& worst_total, Real& rate_max) {
    const Real *se = w.slope(r, 0), *sh = w.slope(r, 1), *ph = w.slope(r, 4);
    const Real *fm = w.face(r, 0), *fm_n = w.face(r + 1, 0), *flo_n = w.face(r + 1, 1), *fhi = w.face(r, 2);
    const Real *ft = w.face(r, 3), *ft_n = w.face(r + 1, 3);
    Real* __restrict clamped = w.clamped();
    Real worst = 0, rate = 0;
    const int c0 = cols.begin + kGhost, c1 = cols.end + kGhost;
    vector_blocks<Real>(c0, c1, worst, rate, [&](int c) __attribute__((always_inline)) {
        const Real rate_h = -(fm_n[c] - fm[c]) * s.idy;
        const Real rate_qy = -(flo_n[c] - fhi[c]) * s.idy - s.g * (h[c] + ph[c]) * (se[c] - sh[c]) * s.idy;
        const Real rate_qx = -(ft_n[c] - ft[c]) * s.idy;
        const Real depth = update_cell<Real, kFriction>(dt, h[c], hv[c], hu[c], rate_h, rate_qy, rate_qx, g_n2[c], friction_dt, s.dry,
                                                        h_out[c], hv_out[c], hu_out[c], clamped[c]);
        const Real cell_rate = kRate ? directional_wave_rate(h_out[c], hu_out[c], hv_out[c], s.g, s.dry, s.idx, s.idy) : Real(0);
        return std::pair<Real, Real>{depth, cell_rate};
    });
    fixes_total += count_clamped(c0, c1, clamped, worst);
    worst_total = min(worst_total, worst);
    rate_max = max(rate_max, rate);
}

}  // namespace flotsam::hydro::split
