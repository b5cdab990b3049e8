// The ray-parallel height-field walk (HeightfieldTraversal::trace_lanes). A stream of rays is
// held as a structure of arrays, a few hundred at a time, and walked in passes: each pass takes
// the walking rays a SIMD vector at a time (Google Highway: 4 lanes of double on AVX2, 8 on
// AVX-512, 2 on SSE4 and the emulated baseline, chosen at run time), steps them cell by cell
// until half of the vector's lanes have finished (a finished lane idles, masked), and the rays
// still walking are compacted for the next pass. The start of every walk (its cell, its sheared
// frame, a beam ray's leap to where its block is clear) is computed for a vector of rays at once
// too. Per lane, every operation is the scalar walk's (heightfield_walk.inc) in the same order,
// in IEEE double without FMA contraction, so a lane finds what the scalar walk at level 0 finds,
// on any instruction set: Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1),
// 2013 (Sec. 3), with the sheared frame's axes chosen per lane by selects, not per ray by
// templates.
// What is rare or long goes to the scalar walk, from the ray's start: rays that cross more than
// 32 cells within the relief (grazing ones, for which the scalar walk jumps and climbs), a miss
// near a cell corner (where the scalar walk also tests the corner's two other cells), a ray past
// its side-wall budget, a beam ray whose leap leaves its plane. Unlike the scalar walk, a lane does
// not jump clear stretches with the dilated blocks: it visits every cell, which changes no hit but
// those within a float ulp of a block's bounds.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "gonio/trace/heightfield_lanes.cpp"
#include "hwy/foreach_target.h" // re-includes this file once per instruction set
#include "hwy/highway.h"

// The edge functions must be exactly antisymmetric and every lane the scalar walk: no FMA.
#pragma GCC optimize("fp-contract=off")

#ifndef GONIO_HEIGHTFIELD_LANES_ONCE
#define GONIO_HEIGHTFIELD_LANES_ONCE
#include "gonio/trace/heightfield_cells.h"
#include "gonio/trace/heightfield_traversal.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace gonio::lanes {

constexpr std::size_t kMaxLanes = 16; // AVX-512's 8 doubles, twice
constexpr std::size_t kBatch = 512;   // rays held at once: their arrays stay in L2

// What the lanes read: the surface and the stream's beam.
struct Grid {
    const float* heights; // (n + 1)^2, row-major
    double stride;        // n + 1
    double n, spacing, inv_spacing, period, pad, corner_tolerance;
    double slab_factor; // relief / spacing: a ray crosses slab_factor * |d_xy|max / |d_z| cells
    double z_top, z_bottom;
    // Rays crossing more cells than this within the relief take the scalar walk, whose jumps over
    // clear blocks beat a lane's cell by cell there (1024^2, against the scalar walk in one run:
    // 85 deg 0.95-0.99 with 64, 1.00-1.04 with 32, 0.98 with 8; 60 deg 1.10-1.12 either way).
    double lane_cells = 32;
    const float* beam_t = nullptr;         // the beam's clear distances (beam_entry), width^2
    double beam_width = 0, beam_scale = 1; // the block of cell i is floor(i * beam_scale)
};

// Per ray, one array each (structure of arrays).
enum Field {
    kOx,
    kOy,
    kOz,
    kDx,
    kDy,
    kDz,
    kMaxWraps,
    kBeam, // given
    kInvDx,
    kInvDy,
    kT,
    kCx,
    kCy,
    kWraps, // the walk
    kKx,
    kKy,
    kKz,
    kShearX,
    kShearY,
    kShearZ,
    kCornerT, // its sheared frame
    kEvent,
    kBest,
    kTri, // what happened: Event, a hit's distance and triangle
    kFields
};
enum Event { kWalking = 0, kHit = 1, kEscaped = 2, kScalar = 3, kIdle = 4 };

struct alignas(64) Arrays {
    double f[kFields][kBatch + kMaxLanes];
};

} // namespace gonio::lanes
#endif

HWY_BEFORE_NAMESPACE();
namespace gonio::lanes::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;

size_t LaneCount() {
    return hn::Lanes(D());
}

// Grid line i as the traversal holds it: double(float(i * spacing)).
HWY_INLINE V Line(const Grid& g, V i) {
    const D d;
    return hn::PromoteTo(d,
                         hn::DemoteTo(hn::Rebind<float, D>(), hn::Mul(i, hn::Set(d, g.spacing))));
}

// walk_cells::cell_of for a vector: the cell of v in [0, period], on a grid line the one the ray
// moves into (direction < 0: the cell below the line).
HWY_INLINE V CellOf(const Grid& g, V v, V direction) {
    const D d;
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0), last = hn::Set(d, g.n - 1);
    V i = hn::Min(hn::Max(hn::Floor(hn::Mul(v, hn::Set(d, g.inv_spacing))), zero), last);
    const auto down = hn::Lt(direction, zero);
    for (;;) {
        const V l = Line(g, i);
        const auto move = hn::And(
            hn::Gt(i, zero), hn::Or(hn::And(down, hn::Le(v, l)), hn::AndNot(down, hn::Lt(v, l))));
        if (hn::AllFalse(d, move)) break;
        i = hn::Sub(i, hn::IfThenElseZero(move, one));
    }
    for (;;) {
        const V l = Line(g, hn::Add(i, one));
        const auto move = hn::And(
            hn::Lt(i, last), hn::Or(hn::And(down, hn::Gt(v, l)), hn::AndNot(down, hn::Ge(v, l))));
        if (hn::AllFalse(d, move)) break;
        i = hn::Add(i, hn::IfThenElseZero(move, one));
    }
    return i;
}

// walk_cells::locate for a vector: v brought into the patch by whole periods, and its cell.
HWY_INLINE V Locate(const Grid& g, V& v, V direction) {
    const D d;
    const V zero = hn::Zero(d), period = hn::Set(d, g.period);
    const auto down = hn::Lt(direction, zero);
    const auto outside = hn::Or(hn::And(down, hn::Or(hn::Le(v, zero), hn::Gt(v, period))),
                                hn::AndNot(down, hn::Or(hn::Lt(v, zero), hn::Ge(v, period))));
    if (!hn::AllFalse(d, outside)) {
        V w = hn::Sub(v, hn::Mul(hn::Floor(hn::Div(v, period)), period));
        const V w_down = hn::Min(hn::IfThenElse(hn::Le(w, zero), hn::Add(w, period), w), period);
        V w_up = hn::IfThenElse(hn::Ge(w, period), hn::Sub(w, period), w);
        w_up = hn::IfThenElse(hn::Lt(w_up, zero), zero, w_up);
        // As the scalar code: (w <= 0 ? w + period : w), then period if above it.
        w = hn::IfThenElse(down, w_down, w_up);
        v = hn::IfThenElse(outside, w, v);
    }
    return CellOf(g, v, direction);
}

// The component of (x, y, z) on axis k (0, 1, 2).
HWY_INLINE V Component(V k, V x, V y, V z) {
    const D d;
    return hn::IfThenElse(hn::Eq(k, hn::Zero(d)), x,
                          hn::IfThenElse(hn::Eq(k, hn::Set(d, 1.0)), y, z));
}

// Every ray's start, a vector at a time: eligibility, cell, sheared frame, a beam ray's leap.
void SetUp(const Grid& g, Arrays& a, size_t count) {
    const D d;
    const size_t N = hn::Lanes(d);
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0), two = hn::Set(d, 2.0);
    const V period = hn::Set(d, g.period);
    for (size_t p = 0; p < count; p += N) {
        auto load = [&](Field f) HWY_ATTR { return hn::Load(d, a.f[f] + p); };
        auto store = [&](Field f, V v) HWY_ATTR { hn::Store(v, d, a.f[f] + p); };
        V ox = load(kOx), oy = load(kOy);
        const V oz = load(kOz), dx = load(kDx), dy = load(kDy), dz = load(kDz);
        V event = load(kEvent);
        // Rays crossing more than lane_cells cells within the relief take the scalar walk.
        const V speed_xy = hn::Max(hn::Abs(dx), hn::Abs(dy));
        const auto eligible = hn::And(
            hn::Ne(dz, zero),
            hn::Le(hn::Mul(hn::Mul(hn::Set(d, g.slab_factor), speed_xy), hn::Abs(hn::Div(one, dz))),
                   hn::Set(d, g.lane_cells)));
        event = hn::IfThenElse(hn::And(hn::Eq(event, zero), hn::Not(eligible)),
                               hn::Set(d, double(kScalar)), event);
        V cx = Locate(g, ox, dx), cy = Locate(g, oy, dy);
        const V inv_dx = hn::IfThenElseZero(hn::Ne(dx, zero), hn::Div(one, dx));
        const V inv_dy = hn::IfThenElseZero(hn::Ne(dy, zero), hn::Div(one, dy));
        const V inv_dz = hn::IfThenElseZero(hn::Ne(dz, zero), hn::Div(one, dz));
        V t = zero, wraps = zero;
        // A beam ray leaps to where its block of origins is known clear (walk_cells::leap).
        const auto beam = hn::And(hn::Eq(load(kBeam), one), hn::Eq(event, zero));
        if (g.beam_t && !hn::AllFalse(d, beam)) {
            const V scale = hn::Set(d, g.beam_scale);
            const V block =
                hn::Add(hn::Mul(hn::Floor(hn::Mul(cy, scale)), hn::Set(d, g.beam_width)),
                        hn::Floor(hn::Mul(cx, scale)));
            const V t0 = hn::IfThenElseZero(
                beam,
                hn::PromoteTo(d, hn::GatherIndex(hn::Rebind<float, D>(), g.beam_t,
                                                 hn::DemoteTo(hn::Rebind<int32_t, D>(),
                                                              hn::IfThenElseZero(beam, block)))));
            const auto leaps = hn::Gt(t0, zero);
            if (!hn::AllFalse(d, leaps)) {
                t = hn::IfThenElse(leaps, t0, t);
                // Out through its plane on the way: rare (the scalar walk counts its walls).
                const V z_stop =
                    hn::IfThenElse(hn::Gt(dz, zero), hn::Set(d, g.z_top), hn::Set(d, g.z_bottom));
                const V stop_sign = hn::IfThenElse(
                    hn::Gt(dz, zero), one, hn::IfThenElseZero(hn::Lt(dz, zero), hn::Neg(one)));
                const auto out = hn::And(
                    leaps,
                    hn::Gt(hn::Mul(hn::Sub(hn::Add(oz, hn::Mul(t, dz)), z_stop), stop_sign), zero));
                event = hn::IfThenElse(out, hn::Set(d, double(kScalar)), event);
                V px = hn::Add(ox, hn::Mul(t, dx)), py = hn::Add(oy, hn::Mul(t, dy));
                auto wrap = [&](V& q, V& o, V dir) HWY_ATTR {
                    for (;;) {
                        const auto below = hn::Lt(dir, zero);
                        const auto need = hn::And(
                            leaps,
                            hn::Or(hn::Or(hn::Gt(q, period), hn::AndNot(below, hn::Eq(q, period))),
                                   hn::Or(hn::Lt(q, zero), hn::And(hn::Eq(q, zero), below))));
                        if (hn::AllFalse(d, need)) return;
                        const V by = hn::IfThenElse(hn::Ge(q, period), hn::Neg(period), period);
                        q = hn::IfThenElse(need, hn::Add(q, by), q);
                        o = hn::IfThenElse(need, hn::Add(o, by), o);
                        wraps = hn::Add(wraps, hn::IfThenElseZero(need, one));
                    }
                };
                wrap(px, ox, dx);
                wrap(py, oy, dy);
                event = hn::IfThenElse(hn::And(leaps, hn::Gt(wraps, load(kMaxWraps))),
                                       hn::Set(d, double(kScalar)), event);
                // Lanes that must not move keep their cell: cell_of of an in-patch point.
                px = hn::IfThenElse(leaps, px, hn::Min(hn::Max(px, zero), period));
                py = hn::IfThenElse(leaps, py, hn::Min(hn::Max(py, zero), period));
                cx = hn::IfThenElse(leaps, CellOf(g, px, dx), cx);
                cy = hn::IfThenElse(leaps, CellOf(g, py, dy), cy);
            }
        }
        // The sheared frame as HeightfieldTraversal::oriented picks it.
        const V ax = hn::Abs(dx), ay = hn::Abs(dy), az = hn::Abs(dz);
        const V kz = hn::IfThenElse(hn::Gt(ax, ay), hn::IfThenElse(hn::Gt(ax, az), zero, two),
                                    hn::IfThenElse(hn::Gt(ay, az), one, two));
        const auto negative = hn::Lt(Component(kz, dx, dy, dz), zero);
        const auto z_axis = hn::Eq(kz, two), x_axis = hn::Eq(kz, zero);
        const V kx = hn::IfThenElse(z_axis, hn::IfThenElse(negative, one, zero),
                                    hn::IfThenElse(x_axis, hn::IfThenElse(negative, two, one),
                                                   hn::IfThenElse(negative, zero, two)));
        const V ky = hn::IfThenElse(z_axis, hn::IfThenElse(negative, zero, one),
                                    hn::IfThenElse(x_axis, hn::IfThenElse(negative, one, two),
                                                   hn::IfThenElse(negative, two, zero)));
        const V shear_z = Component(kz, inv_dx, inv_dy, inv_dz);
        const V inv_speed = hn::IfThenElse(hn::Ge(ax, ay), hn::Abs(inv_dx), hn::Abs(inv_dy));
        store(kOx, ox), store(kOy, oy), store(kInvDx, inv_dx), store(kInvDy, inv_dy);
        store(kT, t), store(kCx, cx), store(kCy, cy), store(kWraps, wraps);
        store(kKx, kx), store(kKy, ky), store(kKz, kz), store(kShearZ, shear_z);
        store(kShearX, hn::Mul(Component(kx, dx, dy, dz), shear_z));
        store(kShearY, hn::Mul(Component(ky, dx, dy, dz), shear_z));
        store(kCornerT, hn::Mul(hn::Set(d, g.corner_tolerance), inv_speed));
        store(kEvent, event);
    }
}

// One pass: every walking ray steps on, a vector at a time, until half of its vector's lanes
// have stopped (kEvent, kBest, kTri then say why) or all of them when `finish`.
void Walk(const Grid& g, Arrays& a, size_t count, bool finish) {
    const D d;
    const hn::Rebind<float, D> df;
    const hn::Rebind<int32_t, D> di;
    const size_t N = hn::Lanes(d);
    const V inf = hn::Set(d, std::numeric_limits<double>::infinity());
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0), two = hn::Set(d, 2.0);
    const V n = hn::Set(d, g.n), last = hn::Set(d, g.n - 1), stride = hn::Set(d, g.stride);
    const V period = hn::Set(d, g.period), pad = hn::Set(d, g.pad);
    const V z_top = hn::Set(d, g.z_top), z_bottom = hn::Set(d, g.z_bottom);
    auto height = [&](V index) HWY_ATTR {
        return hn::PromoteTo(d, hn::GatherIndex(df, g.heights, hn::DemoteTo(di, index)));
    };
    // Stopped lanes that end a vector's pass: half (measured at 1024^2, 60 deg, against the scalar
    // walk in one run: a quarter 1.10-1.16, half 1.10-1.17, three quarters 1.11-1.14,
    // all 1.04-1.06).
    const size_t enough = finish ? N : (N + 1) / 2;
    for (size_t p = 0; p < count; p += N) {
        auto load = [&](Field f) HWY_ATTR { return hn::Load(d, a.f[f] + p); };
        auto store = [&](Field f, V v) HWY_ATTR { hn::Store(v, d, a.f[f] + p); };
        const V oz = load(kOz), dx = load(kDx), dy = load(kDy), dz = load(kDz);
        const V inv_dx = load(kInvDx), inv_dy = load(kInvDy), max_wraps = load(kMaxWraps);
        const V corner_t = load(kCornerT);
        const V kx = load(kKx), ky = load(kKy), kz = load(kKz);
        const V sx = load(kShearX), sy = load(kShearY), sz = load(kShearZ);
        const auto up_x = hn::Gt(dx, zero), up_y = hn::Gt(dy, zero);
        const auto move_x = hn::Ne(dx, zero), move_y = hn::Ne(dy, zero);
        const V step_x = hn::IfThenElse(up_x, one, hn::Neg(one));
        const V step_y = hn::IfThenElse(up_y, one, hn::Neg(one));
        const V z_end = hn::IfThenElse(hn::Gt(dz, zero), inf,
                                       hn::IfThenElse(hn::Lt(dz, zero), hn::Neg(inf), oz));
        const V z_stop = hn::IfThenElse(hn::Gt(dz, zero), z_top, z_bottom);
        const V stop_sign = hn::IfThenElse(hn::Gt(dz, zero), one,
                                           hn::IfThenElseZero(hn::Lt(dz, zero), hn::Neg(one)));
        V ox = load(kOx), oy = load(kOy), t = load(kT), cx = load(kCx), cy = load(kCy);
        V wraps = load(kWraps), event = load(kEvent), best_hit = load(kBest), tri_hit = load(kTri);
        auto active = hn::Eq(event, zero);
        size_t stopped = N - hn::CountTrue(d, active);
        while (stopped < enough) {
            const V x0 = Line(g, cx), x1 = Line(g, hn::Add(cx, one));
            const V y0 = Line(g, cy), y1 = Line(g, hn::Add(cy, one));
            const V tx = hn::IfThenElse(
                move_x, hn::Mul(hn::Sub(hn::IfThenElse(up_x, x1, x0), ox), inv_dx), inf);
            const V ty = hn::IfThenElse(
                move_y, hn::Mul(hn::Sub(hn::IfThenElse(up_y, y1, y0), oy), inv_dy), inf);
            const V t_out = hn::Min(tx, ty);
            const V corner = hn::Add(hn::Mul(cy, stride), cx);
            const V h0 = height(corner), h1 = height(hn::Add(corner, one));
            const V h3 = height(hn::Add(corner, stride)),
                    h2 = height(hn::Add(hn::Add(corner, stride), one));
            const V lo = hn::Min(hn::Min(h0, h1), hn::Min(h3, h2));
            const V hi = hn::Max(hn::Max(h0, h1), hn::Max(h3, h2));
            const V za = hn::Add(oz, hn::Mul(t, dz));
            const auto finite_out = hn::Lt(t_out, inf);
            const V zb = hn::IfThenElse(finite_out, hn::Add(oz, hn::Mul(t_out, dz)), z_end);
            const auto overlap =
                hn::And(active, hn::And(hn::Ge(hn::Add(hn::Max(za, zb), pad), lo),
                                        hn::Le(hn::Sub(hn::Min(za, zb), pad), hi)));
            auto hit = hn::Lt(one, zero); // none
            auto fallback = hit;
            V best = inf, tri = hn::Set(d, -1.0);
            if (!hn::AllFalse(d, overlap)) {
                struct P {
                    V x, y, z;
                };
                auto project = [&](V ax, V ay, V az) HWY_ATTR {
                    const V a_kz = Component(kz, ax, ay, az);
                    return P{hn::Sub(Component(kx, ax, ay, az), hn::Mul(sx, a_kz)),
                             hn::Sub(Component(ky, ax, ay, az), hn::Mul(sy, a_kz)),
                             hn::Mul(sz, a_kz)};
                };
                const V ax0 = hn::Sub(x0, ox), ax1 = hn::Sub(x1, ox);
                const V ay0 = hn::Sub(y0, oy), ay1 = hn::Sub(y1, oy);
                const P v0 = project(ax0, ay0, hn::Sub(h0, oz)),
                        v1 = project(ax1, ay0, hn::Sub(h1, oz));
                const P v2 = project(ax1, ay1, hn::Sub(h2, oz)),
                        v3 = project(ax0, ay1, hn::Sub(h3, oz));
                auto edge = [&](const P& p, const P& q)
                                HWY_ATTR { return hn::Sub(hn::Mul(p.x, q.y), hn::Mul(p.y, q.x)); };
                const V diagonal = edge(v3, v1);
                auto test = [&](V u, V v, V w, const P& a0, const P& b0, const P& c0,
                                V which) HWY_ATTR {
                    const auto negative =
                        hn::Or(hn::Or(hn::Lt(u, zero), hn::Lt(v, zero)), hn::Lt(w, zero));
                    const auto positive =
                        hn::Or(hn::Or(hn::Gt(u, zero), hn::Gt(v, zero)), hn::Gt(w, zero));
                    const V det = hn::Add(hn::Add(u, v), w);
                    const V tt = hn::Div(
                        hn::Add(hn::Add(hn::Mul(u, a0.z), hn::Mul(v, b0.z)), hn::Mul(w, c0.z)),
                        det);
                    const auto ok = hn::AndNot(
                        hn::And(negative, positive),
                        hn::And(hn::Ne(det, zero), hn::And(hn::Ge(tt, zero), hn::Lt(tt, best))));
                    best = hn::IfThenElse(ok, tt, best);
                    tri = hn::IfThenElse(ok, which, tri);
                };
                test(diagonal, edge(v0, v3), edge(v1, v0), v0, v1, v3, zero);
                test(hn::Neg(diagonal), edge(v2, v1), edge(v3, v2), v2, v3, v1, one);
                hit = hn::And(overlap, hn::Ge(tri, zero));
                fallback =
                    hn::AndNot(hit, hn::And(overlap, hn::Le(hn::Abs(hn::Sub(tx, ty)), corner_t)));
            }
            // On to the next cell, through a side wall into the next copy of the patch.
            const V t_next = hn::Max(t, t_out);
            const auto beyond =
                hn::Gt(hn::Mul(hn::Sub(hn::Add(oz, hn::Mul(t_next, dz)), z_stop), stop_sign), zero);
            const auto escaped = hn::And(active, hn::Or(hn::Not(finite_out), beyond));
            V nx = hn::Add(cx, hn::IfThenElseZero(hn::Le(tx, ty), step_x));
            V ny = hn::Add(cy, hn::IfThenElseZero(hn::Le(ty, tx), step_y));
            const auto over_x = hn::Eq(nx, n), under_x = hn::Lt(nx, zero);
            const auto over_y = hn::Eq(ny, n), under_y = hn::Lt(ny, zero);
            nx = hn::IfThenElse(over_x, zero, hn::IfThenElse(under_x, last, nx));
            ny = hn::IfThenElse(over_y, zero, hn::IfThenElse(under_y, last, ny));
            const V wx = hn::IfThenElse(over_x, hn::Sub(ox, period),
                                        hn::IfThenElse(under_x, hn::Add(ox, period), ox));
            const V wy = hn::IfThenElse(over_y, hn::Sub(oy, period),
                                        hn::IfThenElse(under_y, hn::Add(oy, period), oy));
            V nw = hn::Add(wraps, hn::IfThenElseZero(hn::Or(over_x, under_x), one));
            nw = hn::Add(nw, hn::IfThenElseZero(hn::Or(over_y, under_y), one));
            fallback = hn::Or(fallback, hn::AndNot(hit, hn::And(active, hn::Gt(nw, max_wraps))));
            // A hit comes first, then the scalar walk's cases, then the way out.
            const auto stop = hn::Or(hit, hn::Or(fallback, escaped));
            const auto moves = hn::AndNot(stop, active);
            t = hn::IfThenElse(moves, t_next, t);
            cx = hn::IfThenElse(moves, nx, cx), cy = hn::IfThenElse(moves, ny, cy);
            ox = hn::IfThenElse(moves, wx, ox), oy = hn::IfThenElse(moves, wy, oy);
            wraps = hn::IfThenElse(moves, nw, wraps);
            if (!hn::AllFalse(d, stop)) {
                event = hn::IfThenElse(hit, one,
                                       hn::IfThenElse(fallback, hn::Set(d, double(kScalar)),
                                                      hn::IfThenElse(escaped, two, event)));
                best_hit = hn::IfThenElse(hit, best, best_hit);
                tri_hit = hn::IfThenElse(hit, tri, tri_hit);
                active = moves;
                stopped = N - hn::CountTrue(d, active);
            }
        }
        store(kOx, ox), store(kOy, oy), store(kT, t), store(kCx, cx), store(kCy, cy);
        store(kWraps, wraps), store(kEvent, event), store(kBest, best_hit), store(kTri, tri_hit);
    }
}

} // namespace gonio::lanes::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace gonio {
namespace lanes {
HWY_EXPORT(LaneCount);
HWY_EXPORT(SetUp);
HWY_EXPORT(Walk);
} // namespace lanes

void HeightfieldTraversal::trace_lanes(const LaneRay* rays, std::size_t count, double z_top,
                                       double z_bottom, TraversalHit* out) const {
    using namespace lanes;
    if (lanes_ == 0) { // the scalar walk, one by one
        for (std::size_t i = 0; i < count; ++i)
            out[i] = trace(rays[i].o, rays[i].d, z_top, z_bottom, rays[i].max_wraps, rays[i].beam);
        return;
    }
    const std::size_t width = std::size_t(lanes_);
    Grid grid{h_.data(), double(n_ + 1),    double(n_),
              spacing_,  inv_spacing_,      period(),
              pad_,      corner_tolerance_, relief_ * inv_spacing_,
              z_top,     z_bottom};
    // The stream's beam (the first beam ray's): rays of another beam go to the scalar walk.
    const BeamEntry* beam = nullptr;
    for (std::size_t i = 0; i < count && !beam; ++i)
        if (rays[i].beam && rays[i].beam->width > 0) beam = rays[i].beam;
    if (beam) {
        grid.beam_t = beam->t.data(), grid.beam_width = beam->width;
        grid.beam_scale = 1.0 / double(1 << beam->shift);
    }
    thread_local std::vector<Arrays> arrays(1);
    Arrays& a = arrays[0];
    std::size_t ray_of[kBatch + kMaxLanes];
    std::uint16_t keep[kBatch]; // the rays still walking, by their place before compaction
    const double* line = line_.data();
    const std::size_t stride = std::size_t(n_) + 1;
    auto scalar = [&](std::size_t i) {
        out[i] = trace(rays[i].o, rays[i].d, z_top, z_bottom, rays[i].max_wraps, rays[i].beam);
    };
    // The lanes past the last ray: idle, a vertical ray in cell (0, 0) keeps their gathers in
    // the grid.
    auto idle = [&](std::size_t from, std::size_t to) {
        for (std::size_t p = from; p < to; ++p) {
            for (int f = 0; f < kFields; ++f) a.f[f][p] = 0;
            a.f[kDz][p] = 1, a.f[kKy][p] = 1, a.f[kKz][p] = 2, a.f[kShearZ][p] = 1;
            a.f[kEvent][p] = kIdle;
        }
    };
    for (std::size_t first = 0; first < count; first += kBatch) {
        std::size_t live = std::min(kBatch, count - first);
        for (std::size_t k = 0; k < live; ++k) {
            const LaneRay& r = rays[first + k];
            a.f[kOx][k] = r.o.x, a.f[kOy][k] = r.o.y, a.f[kOz][k] = r.o.z;
            a.f[kDx][k] = r.d.x, a.f[kDy][k] = r.d.y, a.f[kDz][k] = r.d.z;
            a.f[kMaxWraps][k] = r.max_wraps;
            const bool of_beam = r.beam && r.beam->width > 0;
            a.f[kBeam][k] = of_beam && r.o.z == beam->z_start && r.d.x == beam->d.x &&
                            r.d.y == beam->d.y && r.d.z == beam->d.z;
            // A ray of another beam than the stream's: the scalar walk.
            a.f[kEvent][k] = of_beam && r.beam != beam ? kScalar : kWalking;
            ray_of[k] = first + k;
        }
        idle(live, live + width);
        HWY_DYNAMIC_DISPATCH(SetUp)(grid, a, live);
        for (;;) {
            // The rays that stopped are completed; the others move up, in order, a field at a
            // time (a ray at a time, its fields 4 KiB apart, took 40 % of this function: perf,
            // 1024^2, theta_i 60 deg).
            std::size_t kept = 0;
            for (std::size_t k = 0; k < live; ++k) {
                const double event = a.f[kEvent][k];
                const std::size_t i = ray_of[k];
                if (event == kWalking) {
                    ray_of[kept] = i, keep[kept] = std::uint16_t(k);
                    ++kept;
                } else if (event == kHit) {
                    // The scalar walk's found() for cell (cx, cy) of this copy of the patch.
                    const int tri = int(a.f[kTri][k]), cx = int(a.f[kCx][k]), cy = int(a.f[kCy][k]);
                    const double best = a.f[kBest][k];
                    const float* r0 = h_.data() + std::size_t(cy) * stride + std::size_t(cx);
                    const float* r1 = r0 + stride;
                    const double sx = line[cx + 1] - line[cx], sy = line[cy + 1] - line[cy];
                    TraversalHit& r = out[i];
                    r = TraversalHit{};
                    r.normal = tri == 0 ? Vec3{-(double(r0[1]) - r0[0]) * sy,
                                               -(double(r1[0]) - r0[0]) * sx, sx * sy}
                                        : Vec3{(double(r1[0]) - r1[1]) * sy,
                                               (double(r0[1]) - r1[1]) * sx, sx * sy};
                    r.kind = TraversalHit::hit;
                    r.t = best;
                    const double L = line[n_];
                    Vec3 at{a.f[kOx][k] + best * a.f[kDx][k], a.f[kOy][k] + best * a.f[kDy][k],
                            a.f[kOz][k] + best * a.f[kDz][k]};
                    if (at.x < 0) at.x += L;
                    if (at.x >= L) at.x -= L;
                    if (at.y < 0) at.y += L;
                    if (at.y >= L) at.y -= L;
                    r.position = at;
                    r.cell_x = cx, r.cell_y = cy, r.triangle = tri;
                    r.wraps = int(a.f[kWraps][k]);
                } else if (event == kEscaped) {
                    const double dz = a.f[kDz][k];
                    TraversalHit& r = out[i];
                    r = TraversalHit{};
                    r.kind = dz > 0   ? TraversalHit::escaped_up
                             : dz < 0 ? TraversalHit::escaped_down
                                      : TraversalHit::lost;
                    r.wraps = int(a.f[kWraps][k]);
                } else { // rare: the scalar walk from the ray's start
                    scalar(i);
                }
            }
            std::size_t moved = 0; // the rays before the first that stopped stay
            while (moved < kept && keep[moved] == moved) ++moved;
            if (moved < kept)
                for (int f = 0; f < kFields; ++f) {
                    double* field = a.f[f];
                    for (std::size_t j = moved; j < kept; ++j) field[j] = field[keep[j]];
                }
            live = kept;
            if (live == 0) break;
            idle(live, live + width);
            // The last few rays: every lane to its end (a pass that waits for half of a vector
            // would not move a vector of one ray and idle lanes).
            HWY_DYNAMIC_DISPATCH(Walk)(grid, a, live, live <= 4 * width);
        }
    }
}

int HeightfieldTraversal::native_lanes() {
    return int(HWY_DYNAMIC_DISPATCH(lanes::LaneCount)());
}

std::vector<std::pair<std::string, std::int64_t>> HeightfieldTraversal::lane_targets() {
    std::vector<std::pair<std::string, std::int64_t>> out;
    const std::uint64_t have = std::uint64_t(hwy::SupportedTargets() & HWY_TARGETS);
    for (int k = 0; k < 64; ++k) // every bit a target, EMU128 and SCALAR the highest
        if (const std::uint64_t bit = std::uint64_t(1) << k; have & bit)
            out.emplace_back(hwy::TargetName(std::int64_t(bit)), std::int64_t(bit));
    return out;
}

} // namespace gonio
#endif
