#include "gonio/trace/heightfield_traversal.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tbb/parallel_for.h>

// The edge functions must be exactly antisymmetric (see the header): no fused multiply-add.
#pragma GCC optimize("fp-contract=off")

namespace gonio {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// A vertex in the ray's sheared frame (Woop et al. 2013, Sec. 3): the ray runs along +z' from the
// origin, x' and y' are where the vertex lies across it, z' is its distance along it times 1/d_kz.
struct Projected {
    double x, y, z;
};
[[gnu::always_inline]] inline double edge(const Projected& p, const Projected& q) {
    return p.x * q.y - p.y * q.x;
}
} // namespace

HeightfieldTraversal::HeightfieldTraversal(const HeightField& s) : n_(s.n) {
    if (s.n < 2) throw std::invalid_argument("HeightfieldTraversal: grid size must be >= 2");
    const int n = n_, v = n + 1;
    inv_spacing_ = 1.0 / s.spacing;
    spacing_ = s.spacing;
    line_.resize(size_t(v));
    for (int i = 0; i < v; ++i) line_[size_t(i)] = double(float(i * s.spacing));
    h_.resize(size_t(v) * size_t(v));
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (int y = 0; y < v; ++y)
        for (int x = 0; x < v; ++x) {
            const float z = s.at(x, y);
            h_[size_t(y) * size_t(v) + size_t(x)] = z;
            lo = std::min(lo, z), hi = std::max(hi, z);
        }
    const double extent = std::max({period(), std::abs(double(lo)), std::abs(double(hi))});
    // A float ulp of the coordinates: far above the double rounding of the walk's crossing
    // times, far below any height difference that matters.
    pad_ = extent * std::numeric_limits<float>::epsilon();
    relief_ = double(hi) - double(lo);
    corner_tolerance_ = extent * 1e-10;

    // Level 1 from the vertices, then each level from the one below; a node at level l covers
    // cells [i 2^l, min((i + 1) 2^l, n)) and so the vertices up to the far edge.
    std::vector<std::vector<float>> levels(1); // level 0: the cells themselves
    level_width_.push_back(n);
    for (int l = 1;; ++l) {
        const int w = (n + (1 << l) - 1) >> l;
        std::vector<float> node(2 * size_t(w) * size_t(w));
        if (l == 1) {
            for (int j = 0; j < w; ++j)
                for (int i = 0; i < w; ++i) {
                    float a = std::numeric_limits<float>::max(), b = -a;
                    for (int y = 2 * j; y <= std::min(2 * j + 2, n); ++y)
                        for (int x = 2 * i; x <= std::min(2 * i + 2, n); ++x) {
                            const float z = h_[size_t(y) * size_t(v) + size_t(x)];
                            a = std::min(a, z), b = std::max(b, z);
                        }
                    node[2 * (size_t(j) * w + i)] = a, node[2 * (size_t(j) * w + i) + 1] = b;
                }
        } else {
            const std::vector<float>& below = levels.back();
            const int wb = level_width_.back();
            for (int j = 0; j < w; ++j)
                for (int i = 0; i < w; ++i) {
                    float a = std::numeric_limits<float>::max(), b = -a;
                    for (int y = 2 * j; y < std::min(2 * j + 2, wb); ++y)
                        for (int x = 2 * i; x < std::min(2 * i + 2, wb); ++x) {
                            a = std::min(a, below[2 * (size_t(y) * wb + x)]);
                            b = std::max(b, below[2 * (size_t(y) * wb + x) + 1]);
                        }
                    node[2 * (size_t(j) * w + i)] = a, node[2 * (size_t(j) * w + i) + 1] = b;
                }
        }
        levels.push_back(std::move(node));
        level_width_.push_back(w);
        if (w == 1) {
            top_ = l;
            break;
        }
    }
    for (const std::vector<float>& l : levels) {
        level_offset_.push_back(pyramid_.size());
        pyramid_.insert(pyramid_.end(), l.begin(), l.end());
    }

    // The dilated blocks: each block's vertices widened by r cells on every side (periodic).
    for (int k = 0; k < kJumps; ++k) {
        const int b = 1 << kJumpShift[k];
        if (n < 4 * b) break;
        const int w = (n + b - 1) / b;
        std::vector<float> m(2 * size_t(w) * size_t(w));
        // Per vertex row, the running (min, max) over x in [x0 - b, x1 + b] for each block.
        std::vector<float> rows(2 * size_t(w) * size_t(n));
        for (int y = 0; y < n; ++y)
            for (int i = 0; i < w; ++i) {
                float a = std::numeric_limits<float>::max(), c = -a;
                for (int x = i * b - b; x <= std::min((i + 1) * b, n) + b; ++x) {
                    const float z = h_[size_t(y) * size_t(v) + size_t(((x % n) + n) % n)];
                    a = std::min(a, z), c = std::max(c, z);
                }
                rows[2 * (size_t(y) * w + i)] = a, rows[2 * (size_t(y) * w + i) + 1] = c;
            }
        for (int j = 0; j < w; ++j)
            for (int i = 0; i < w; ++i) {
                float a = std::numeric_limits<float>::max(), c = -a;
                for (int y = j * b - b; y <= std::min((j + 1) * b, n) + b; ++y) {
                    const size_t row = size_t(((y % n) + n) % n);
                    a = std::min(a, rows[2 * (row * w + i)]);
                    c = std::max(c, rows[2 * (row * w + i) + 1]);
                }
                m[2 * (size_t(j) * w + i)] = a, m[2 * (size_t(j) * w + i) + 1] = c;
            }
        dilated_[k] = std::move(m);
        dilated_width_[k] = w;
        jumps_ = k + 1;
    }

    // The beam windows: the maximum along x over each row, then along y over those (periodic),
    // at every other cell.
    {
        const int span = (1 << kBeamShift) + 6; // vertices i - 1 .. i + b + 4
        const int w = (n + 1) / 2;
        std::vector<int> wrapped(size_t(n) + size_t(span)); // (i - 1) mod n, i in [0, n + span)
        for (int i = 0; i < n + span; ++i) wrapped[size_t(i)] = (i - 1 + n) % n;
        std::vector<float> rows(size_t(n) * size_t(w));
        beam_window_.resize(size_t(w) * size_t(w));
        tbb::parallel_for(0, n, [&](int y) {
            const float* row = h_.data() + size_t(y) * size_t(v);
            for (int i = 0; i < w; ++i) {
                float c = row[wrapped[size_t(2 * i)]];
                for (int k = 1; k < span; ++k) c = std::max(c, row[wrapped[size_t(2 * i + k)]]);
                rows[size_t(y) * size_t(w) + size_t(i)] = c;
            }
        });
        tbb::parallel_for(0, w, [&](int j) {
            float* out = beam_window_.data() + size_t(j) * size_t(w);
            const float* first = rows.data() + size_t(wrapped[size_t(2 * j)]) * size_t(w);
            std::copy(first, first + w, out);
            for (int k = 1; k < span; ++k) {
                const float* r = rows.data() + size_t(wrapped[size_t(2 * j + k)]) * size_t(w);
                for (int i = 0; i < w; ++i) out[i] = std::max(out[i], r[i]);
            }
        });
    }
}

BeamEntry HeightfieldTraversal::beam_entry(const Vec3& d, double z_start, long long rays) const {
    BeamEntry e;
    e.d = d, e.z_start = z_start, e.shift = kBeamShift;
    const double speed_xy = std::max(std::abs(d.x), std::abs(d.y));
    // Rays that cross many cells within the relief (grazing ones) have the pyramid instead.
    if (!(d.z < 0) || relief_ * inv_spacing_ * speed_xy > 128 * -d.z) return e;
    const int b = 1 << kBeamShift, w = (n_ + b - 1) >> kBeamShift;
    // A block costs about what 1.5 rays save (1024^2, theta_i 60 deg: 520 instructions against
    // 340 per beam ray, callgrind).
    if (rays < 2 * (long long)w * w) return e;
    e.width = w;
    e.t.resize(size_t(w) * size_t(w));
    // Steps of just under one cell of travel, up to a quarter of the patch (so that the walk's
    // leap there crosses at most one side wall per axis).
    const double step = speed_xy > 0 ? 0.99 * spacing_ / speed_xy : kInf;
    const int steps = speed_xy > 0 ? std::max(1, n_ / 4) : 1;
    const int n = n_;
    const size_t window = size_t(n + 1) / 2; // beam_window_ per row
    const double inv_dz = 1.0 / d.z;
    // The cell of coordinate v (v within a quarter period of the patch), periodic; truncation
    // with a correction is the floor (std::floor is a library call without SSE4.1).
    auto cell = [n, inv = inv_spacing_](double v) {
        const double g = v * inv;
        int i = int(g);
        i -= int(g < double(i));
        return i < 0 ? i + n : i >= n ? i - n : i;
    };
    tbb::parallel_for(0, w, [&](int bj) {
        for (int bi = 0; bi < w; ++bi) {
            const double x0 = bi * b * spacing_, y0 = bj * b * spacing_;
            double clear = 0;
            for (int k = 0; k < steps; ++k) {
                const double ta = k == 0 ? 0.0 : k * step, tb = (k + 1) * step;
                // The cells the block's rays cross in [ta, tb] start at (i, j) (a cell to spare).
                const double xa = speed_xy > 0 ? x0 + std::min(ta * d.x, tb * d.x) : x0;
                const double ya = speed_xy > 0 ? y0 + std::min(ta * d.y, tb * d.y) : y0;
                const double bound =
                    double(beam_window_[size_t(cell(ya) >> 1) * window + size_t(cell(xa) >> 1)]) +
                    2 * pad_;
                // Clear while the ray's height (falling) stays above the bound.
                const double t_reach = (bound - z_start) * inv_dz;
                if (!(t_reach > tb)) {
                    clear = std::max(ta, t_reach);
                    break;
                }
                clear = tb;
            }
            // Rounded down to float.
            float c = float(clear);
            if (double(c) > clear) c = std::nextafter(c, 0.0f);
            e.t[size_t(bj) * size_t(w) + size_t(bi)] = c;
        }
    });
    return e;
}

std::size_t HeightfieldTraversal::memory_bytes() const {
    std::size_t bytes = line_.size() * sizeof(double) + h_.size() * sizeof(float);
    bytes += pyramid_.size() * sizeof(float) + beam_window_.size() * sizeof(float);
    for (const std::vector<float>& m : dilated_) bytes += m.size() * sizeof(float);
    return bytes;
}

double HeightfieldTraversal::height_at(double x, double y) const {
    const size_t stride = size_t(n_) + 1;
    return HeightField::triangulated_height(
        x * inv_spacing_, y * inv_spacing_, n_, nullptr, nullptr,
        [&](int i, int j) { return h_[size_t(j) * stride + size_t(i)]; });
}

namespace {
// The cell of the patch's copy that holds coordinate v, bringing v into the patch by whole
// periods; `lines` are the n + 1 grid lines. On a grid line, the cell the ray moves into: a ray
// moving down the axis takes the cell below the line (so v = period stays in the last cell).
[[gnu::always_inline]] inline int locate(double& v, double direction, const double* lines, int n,
                                         double inv_spacing) {
    const double period = lines[n];
    if (direction < 0) { // v in (0, period], lines[i] < v <= lines[i + 1]
        if (v <= 0 || v > period) {
            v -= std::floor(v / period) * period;
            if (v <= 0) v += period;
            if (v > period) v = period;
        }
        int i = std::clamp(int(v * inv_spacing), 0, n - 1);
        while (i > 0 && v <= lines[i]) --i;
        while (i < n - 1 && v > lines[i + 1]) ++i;
        return i;
    }
    if (v < 0 || v >= period) { // v in [0, period), lines[i] <= v < lines[i + 1]
        v -= std::floor(v / period) * period;
        if (v >= period) v -= period; // rounding of the line above
        if (v < 0) v = 0;
    }
    int i = std::clamp(int(v * inv_spacing), 0, n - 1);
    while (i > 0 && v < lines[i]) --i;
    while (i < n - 1 && v >= lines[i + 1]) ++i;
    return i;
}

// The cell of v in [0, period], on a grid line the one the ray moves into.
[[gnu::always_inline]] inline int cell_of(double v, double direction, const double* lines, int n,
                                          double inv_spacing) {
    int i = std::clamp(int(v * inv_spacing), 0, n - 1);
    if (direction < 0) {
        while (i > 0 && v <= lines[i]) --i;
        while (i < n - 1 && v > lines[i + 1]) ++i;
    } else {
        while (i > 0 && v < lines[i]) --i;
        while (i < n - 1 && v >= lines[i + 1]) ++i;
    }
    return i;
}

// The cell in [lo, hi] that holds v (an exit point on a node's face), taking, within `tolerance`
// of a grid line, the cell the ray comes from (the walk then steps on at once).
[[gnu::always_inline]] inline int locate_within(double v, double direction, int lo, int hi,
                                                const double* lines, double inv_spacing,
                                                double tolerance) {
    int i = std::clamp(int(v * inv_spacing), lo, hi); // v >= 0 up to rounding: truncation
    while (i > lo && v < lines[i]) --i;
    while (i < hi && v >= lines[i + 1]) ++i;
    if (direction > 0 && i > lo && v - lines[i] < tolerance) --i;
    if (direction < 0 && i < hi && lines[i + 1] - v < tolerance) ++i;
    return i;
}
} // namespace

TraversalHit HeightfieldTraversal::trace(const Vec3& o, const Vec3& d, double z_top,
                                         double z_bottom, int max_wraps,
                                         const BeamEntry* beam) const {
    // The dominant axis becomes z' of the sheared frame; the other two keep the winding.
    const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
    const int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    const double dz = kz == 0 ? d.x : kz == 1 ? d.y : d.z;
    // Conditional branches, not a jump table: a beam's rays alternate between a few of these,
    // which the branch predictor follows and an indirect jump did not (callgrind, 1024^2,
    // theta_i 60 deg: 0.7 mispredicted jumps per call before).
    if (kz == 2)
        return dz < 0 ? walk<1, 0, 2>(o, d, z_top, z_bottom, max_wraps, beam)
                      : walk<0, 1, 2>(o, d, z_top, z_bottom, max_wraps, beam);
    if (kz == 0)
        return dz < 0 ? walk<2, 1, 0>(o, d, z_top, z_bottom, max_wraps, beam)
                      : walk<1, 2, 0>(o, d, z_top, z_bottom, max_wraps, beam);
    return dz < 0 ? walk<0, 2, 1>(o, d, z_top, z_bottom, max_wraps, beam)
                  : walk<2, 0, 1>(o, d, z_top, z_bottom, max_wraps, beam);
}

template <int KX, int KY, int KZ>
TraversalHit HeightfieldTraversal::walk(const Vec3& o, const Vec3& d, double z_top, double z_bottom,
                                        int max_wraps, const BeamEntry* beam) const {
    TraversalHit r;
    int wraps = 0; // in a register: r is the returned object, in memory
    const int n = n_;
    const double* line = line_.data();
    const float* heights = h_.data();
    const double period = line[n];
    const size_t stride = size_t(n) + 1;
    double ox = o.x, oy = o.y;
    const double oz = o.z;
    int cx = locate(ox, d.x, line, n, inv_spacing_);
    int cy = locate(oy, d.y, line, n, inv_spacing_);
    const bool move_x = d.x != 0, move_y = d.y != 0;
    const bool up_x = d.x > 0, up_y = d.y > 0;
    // Three divisions per ray; everything else is derived from them.
    const double inv_dx = move_x ? 1.0 / d.x : 0.0, inv_dy = move_y ? 1.0 / d.y : 0.0;
    const double inv_dz = d.z != 0 ? 1.0 / d.z : 0.0;
    const double speed_xy = std::max(std::abs(d.x), std::abs(d.y));
    const double inv_speed = std::abs(d.x) >= std::abs(d.y) ? std::abs(inv_dx) : std::abs(inv_dy);
    const double corner_t = corner_tolerance_ * inv_speed;
    const double dd[3] = {d.x, d.y, d.z}, inv[3] = {inv_dx, inv_dy, inv_dz};
    const double shear_z = inv[KZ], shear_x = dd[KX] * shear_z, shear_y = dd[KY] * shear_z;

    // The nearest hit at t in [0, best) on the two triangles of cell (i, j), whose copy of the
    // patch lies (bx, by) away: the triangle, or -1.
    auto hit_cell = [&](int i, int j, double bx, double by, double& best)
        __attribute__((always_inline)) {
        const float* r0 = heights + size_t(j) * stride + size_t(i);
        const float* r1 = r0 + stride;
        const double x0 = line[i] + bx - ox, x1 = line[i + 1] + bx - ox;
        const double y0 = line[j] + by - oy, y1 = line[j + 1] + by - oy;
        auto project = [&](double x, double y, double z) __attribute__((always_inline)) {
            const double a[3] = {x, y, z - oz};
            return Projected{a[KX] - shear_x * a[KZ], a[KY] - shear_y * a[KZ], shear_z * a[KZ]};
        };
        const Projected v0 = project(x0, y0, r0[0]), v1 = project(x1, y0, r0[1]);
        const Projected v2 = project(x1, y1, r1[1]), v3 = project(x0, y1, r1[0]);
        const double diagonal = edge(v3, v1); // shared: triangle B uses its negation
        int found = -1;
        auto test = [&](double u, double v, double w, const Projected& a, const Projected& b,
                        const Projected& c, int which) __attribute__((always_inline)) {
            // Outside when the edge functions differ in sign (one branch: as good as random).
            if (((u < 0) | (v < 0) | (w < 0)) & ((u > 0) | (v > 0) | (w > 0))) return;
            const double det = u + v + w;
            if (det == 0) return; // the ray lies in the triangle's plane
            const double t = (u * a.z + v * b.z + w * c.z) / det;
            if (t >= 0 && t < best) best = t, found = which;
        };
        test(diagonal, edge(v0, v3), edge(v1, v0), v0, v1, v3, 0);
        test(-diagonal, edge(v2, v1), edge(v3, v2), v2, v3, v1, 1);
        return found;
    };

    // The hit on triangle `tri` of cell (i, j), in the copy of the patch (bx, by) away.
    auto found = [&](int tri, int i, int j, double bx, double by, double best)
        __attribute__((always_inline)) {
        const float* r0 = heights + size_t(j) * stride + size_t(i);
        const float* r1 = r0 + stride;
        const double sx = line[i + 1] - line[i], sy = line[j + 1] - line[j];
        // The cross product of the triangle's edges (see heightfield.h for the split).
        r.normal = tri == 0
                       ? Vec3{-(double(r0[1]) - r0[0]) * sy, -(double(r1[0]) - r0[0]) * sx, sx * sy}
                       : Vec3{(double(r1[0]) - r1[1]) * sy, (double(r0[1]) - r1[1]) * sx, sx * sy};
        r.kind = TraversalHit::hit;
        r.t = best;
        // In the hit cell's copy of the patch, then brought into [0, period) (it lies within
        // rounding of cell (i, j)).
        Vec3 at{ox - bx + best * d.x, oy - by + best * d.y, oz + best * d.z};
        if (at.x < 0) at.x += period;
        if (at.x >= period) at.x -= period;
        if (at.y < 0) at.y += period;
        if (at.y >= period) at.y -= period;
        r.position = at;
        r.cell_x = i, r.cell_y = j, r.triangle = tri;
        r.wraps = wraps;
        return r;
    };
    // The two cells beside the corner of cell (cx, cy) the ray passes near: tested when the
    // rounding of the two crossing times could order them wrongly (or step past both).
    auto near_corner = [&](int cx, int cy, double& best, int& hx, int& hy, double& bx_hit,
                           double& by_hit) __attribute__((always_inline)) {
        int tri = -1;
        for (int side = 0; side < 2; ++side) {
            int ex = cx, ey = cy;
            double bx = 0, by = 0;
            if (side == 0)
                ex += up_x ? 1 : -1;
            else
                ey += up_y ? 1 : -1;
            if (ex == n) ex = 0, bx = period;
            if (ex < 0) ex = n - 1, bx = -period;
            if (ey == n) ey = 0, by = period;
            if (ey < 0) ey = n - 1, by = -period;
            const int f = hit_cell(ex, ey, bx, by, best);
            if (f >= 0) tri = f, hx = ex, hy = ey, bx_hit = bx, by_hit = by;
        }
        return tri;
    };

    double t = 0;
    int level = 0;
    // The cells the ray crosses while within the surface's heights: few, and walking them one
    // by one beats any climbing (measured: 1024^2, theta_i 60 deg); many (grazing rays), and the
    // pyramid pays once a few cells in a row were clear.
    const double slab_cells =
        d.z != 0 ? relief_ * inv_spacing_ * speed_xy * std::abs(inv_dz) : kInf;
    const int climb_after = slab_cells <= 64 ? std::numeric_limits<int>::max() : 4;
    // A jump of r cells of travel (less a hundredth of a cell for the grid lines' rounding).
    bool jump_ok = jumps_ > 0 && speed_xy > 0 && slab_cells <= 1024;
    double jump_t[kJumps] = {0, 0};
    const double min_jump_t = spacing_ * inv_speed; // shorter than a cell: walk it instead
    const float* dilated[kJumps] = {nullptr, nullptr};
    size_t dilated_width[kJumps] = {0, 0};
    for (int k = 0; k < jumps_; ++k) {
        jump_t[k] = ((1 << kJumpShift[k]) - 0.01) * spacing_ * inv_speed;
        dilated[k] = dilated_[k].data(), dilated_width[k] = size_t(dilated_width_[k]);
    }
    const int ux = up_x ? 1 : 0, uy = up_y ? 1 : 0;
    const int step_x = up_x ? 1 : -1, step_y = up_y ? 1 : -1;
    const double z_end = d.z > 0 ? kInf : d.z < 0 ? -kInf : oz; // the ray's height at t = inf
    auto escaped = [&]() __attribute__((always_inline)) {
        r.kind = d.z > 0   ? TraversalHit::escaped_up
                 : d.z < 0 ? TraversalHit::escaped_down
                           : TraversalHit::lost;
        r.wraps = wraps;
        return r;
    };
    auto lost = [&]() __attribute__((always_inline)) { // past max_wraps walls
        r.kind = TraversalHit::lost;
        r.wraps = wraps;
        return r;
    };
    // Past the plane the ray leaves through: z > z_top going up, z < z_bottom going down.
    const double z_stop = d.z > 0 ? z_top : z_bottom, stop_sign = d.z > 0 ? 1 : d.z < 0 ? -1 : 0;
    auto beyond = [&](double z) __attribute__((always_inline)) {
        return (z - z_stop) * stop_sign > 0;
    };
    // Through a side wall: the next copy of the patch, the origin moved back by a period.
    auto wrap = [&]() __attribute__((always_inline)) {
        if (cx == n) cx = 0, ox -= period, ++wraps;
        if (cx < 0) cx = n - 1, ox += period, ++wraps;
        if (cy == n) cy = 0, oy -= period, ++wraps;
        if (cy < 0) cy = n - 1, oy += period, ++wraps;
        return wraps > max_wraps;
    };
    // On to t_new over a stretch clear of the surface, which crosses at most one side wall per
    // axis: 0, or 1 when the ray left through its plane on the way, 2 when past max_wraps walls.
    auto leap = [&](double t_new) __attribute__((always_inline)) {
        t = t_new;
        const int wraps_before = wraps;
        // When the leap crossed a side wall in x and in y (it can cross both).
        double wall_tx = kInf, wall_ty = kInf;
        double px = ox + t * d.x, py = oy + t * d.y;
        if (px > period || (px == period && !(d.x < 0)) || px < 0 || (px == 0 && d.x < 0)) {
            const bool over = px >= period;
            wall_tx = ((over ? period : 0.0) - ox) * inv_dx;
            px += over ? -period : period, ox += over ? -period : period;
            ++wraps;
        }
        if (py > period || (py == period && !(d.y < 0)) || py < 0 || (py == 0 && d.y < 0)) {
            const bool over = py >= period;
            wall_ty = ((over ? period : 0.0) - oy) * inv_dy;
            py += over ? -period : period, oy += over ? -period : period;
            ++wraps;
        }
        if (beyond(oz + t * d.z)) {
            // Out through the top (or bottom) plane: only the walls crossed before it count.
            const double plane_t = ((d.z > 0 ? z_top : z_bottom) - oz) * inv_dz;
            wraps = wraps_before + int(wall_tx < plane_t) + int(wall_ty < plane_t);
            return 1;
        }
        if (wraps > max_wraps) return 2;
        cx = cell_of(px, d.x, line, n, inv_spacing_);
        cy = cell_of(py, d.y, line, n, inv_spacing_);
        return 0;
    };
    // A ray of the beam starts where its block of origins is known clear.
    if (beam && beam->width > 0 && oz == beam->z_start && d.x == beam->d.x && d.y == beam->d.y &&
        d.z == beam->d.z) {
        const double t0 =
            beam->t[size_t(cy >> beam->shift) * size_t(beam->width) + size_t(cx >> beam->shift)];
        if (t0 > 0) {
            if (const int left = leap(t0)) return left == 1 ? escaped() : lost();
            // Within a few cells of its hit now: a jump would fail (measured at 1024^2,
            // theta_i 60 deg: 4 in 10^4 of them did not, for 2.9 tries per ray).
            jump_ok = false;
        }
    }
    for (;;) {
        if (level == 0) {
            // Cell by cell, near the surface: the cell's four corners bound its two triangles.
            for (int skipped = 0, clear = 1;;) {
                // Clear of the surface: jump the next r cells of travel whole when the ray's
                // heights over them miss every height within r cells of the block.
                if (clear && jump_ok) {
                    // The longest clear stretch either block size allows: all of its r cells,
                    // or until the ray's height reaches the block's bound, if sooner.
                    double step = 0;
                    const double za = oz + t * d.z;
                    for (int k = 0; k < jumps_; ++k) {
                        const float* m =
                            dilated[k] + 2 * (size_t(cy >> kJumpShift[k]) * dilated_width[k] +
                                              size_t(cx >> kJumpShift[k]));
                        double s_k = 0;
                        const double over = za - (double(m[1]) + pad_);  // > 0: above the block
                        const double under = (double(m[0]) - pad_) - za; // > 0: below it
                        if (over > 0)
                            s_k = d.z >= 0 ? jump_t[k] : std::min(jump_t[k], over * -inv_dz);
                        else if (under > 0)
                            s_k = d.z <= 0 ? jump_t[k] : std::min(jump_t[k], under * inv_dz);
                        step = std::max(step, s_k);
                        // The larger block's region holds the smaller one's: it can only jump
                        // further when the smaller block was cleared whole.
                        if (s_k < jump_t[k]) break;
                    }
                    if (step > min_jump_t) {
                        ++skipped;
                        const int jumped_x = cx, jumped_y = cy;
                        if (const int left = leap(t + step)) return left == 1 ? escaped() : lost();
                        // Jumps count as clear cells: a grazing ray far above the surface
                        // climbs the pyramid instead of jumping r cells at a time (256^2,
                        // theta_i 89 deg: +17 % beam rays/s on one thread).
                        if (skipped >= climb_after && top_ > 0) {
                            const unsigned changed =
                                unsigned(jumped_x ^ cx) | unsigned(jumped_y ^ cy);
                            const int highest = changed ? 31 - __builtin_clz(changed) : 0;
                            level = std::max(1, std::min(highest, top_));
                            break;
                        }
                        continue;
                    }
                }
                clear = 0;
                const double tx = move_x ? (line[cx + ux] - ox) * inv_dx : kInf;
                const double ty = move_y ? (line[cy + uy] - oy) * inv_dy : kInf;
                const double t_out = std::min(tx, ty);
                const float* r0 = heights + size_t(cy) * stride + size_t(cx);
                const float* r1 = r0 + stride;
                const float lo = std::min(std::min(r0[0], r0[1]), std::min(r1[0], r1[1]));
                const float hi = std::max(std::max(r0[0], r0[1]), std::max(r1[0], r1[1]));
                const double za = oz + t * d.z;
                const double zb = t_out < kInf ? oz + t_out * d.z : z_end;
                if (std::max(za, zb) + pad_ >= lo && std::min(za, zb) - pad_ <= hi) {
                    skipped = 0;
                    double best = kInf, bx = 0, by = 0;
                    int hx = cx, hy = cy;
                    int tri = hit_cell(cx, cy, 0, 0, best);
                    if (tri < 0 && std::abs(tx - ty) <= corner_t)
                        tri = near_corner(cx, cy, best, hx, hy, bx, by);
                    if (tri >= 0) return found(tri, hx, hy, bx, by, best);
                } else {
                    ++skipped, clear = 1;
                }
                if (!(t_out < kInf)) return escaped();
                t = std::max(t, t_out);
                if (beyond(oz + t * d.z)) return escaped();
                const int old_x = cx, old_y = cy;
                // Branch-free steps: which axis comes first is as good as random.
                cx += int(tx <= ty) * step_x;
                cy += int(ty <= tx) * step_y;
                if ((unsigned(cx) >= unsigned(n) || unsigned(cy) >= unsigned(n)) && wrap()) {
                    return lost();
                }
                // Clear of the surface for a while: look further ahead from a coarser level.
                if (skipped >= climb_after && top_ > 0) {
                    const unsigned changed = unsigned(old_x ^ cx) | unsigned(old_y ^ cy);
                    const int highest = changed ? 31 - __builtin_clz(changed) : 0;
                    level = std::max(1, std::min(highest, top_));
                    break;
                }
            }
            continue;
        }
        // A coarse node: skipped whole if the ray's heights across it miss its min-max range.
        const int x0 = (cx >> level) << level, y0 = (cy >> level) << level;
        const int x1 = std::min(x0 + (1 << level), n), y1 = std::min(y0 + (1 << level), n);
        const double tx = move_x ? (line[up_x ? x1 : x0] - ox) * inv_dx : kInf;
        const double ty = move_y ? (line[up_y ? y1 : y0] - oy) * inv_dy : kInf;
        const double t_out = std::min(tx, ty);
        const float* node =
            pyramid_.data() + level_offset_[size_t(level)] +
            2 * (size_t(cy >> level) * size_t(level_width_[size_t(level)]) + (cx >> level));
        const double za = oz + t * d.z;
        const double zb = t_out < kInf ? oz + t_out * d.z : z_end;
        if (std::max(za, zb) + pad_ >= node[0] && std::min(za, zb) - pad_ <= node[1]) {
            --level;
            continue;
        }
        if (!(t_out < kInf)) return escaped();
        t = std::max(t, t_out);
        if (beyond(oz + t * d.z)) return escaped();
        const int old_x = cx, old_y = cy;
        const bool step_x = tx <= ty, step_y = ty <= tx;
        if (step_x) cx = up_x ? x1 : x0 - 1;
        if (step_y) cy = up_y ? y1 : y0 - 1;
        if (wrap()) {
            return lost();
        }
        // Out through one face: where along the other axis (a ray that does not move along it
        // stays in its cell there, which is the one locate_within would find).
        if (!step_y && move_y)
            cy =
                locate_within(oy + t * d.y, d.y, y0, y1 - 1, line, inv_spacing_, corner_tolerance_);
        if (!step_x && move_x)
            cx =
                locate_within(ox + t * d.x, d.x, x0, x1 - 1, line, inv_spacing_, corner_tolerance_);
        // The highest level whose node the step changed: look at the new node from there (the
        // nodes above are those the ray was already in, which it overlapped).
        const unsigned changed = unsigned(old_x ^ cx) | unsigned(old_y ^ cy);
        const int highest = changed ? 31 - __builtin_clz(changed) : 0;
        level = std::max(level, std::min(highest, top_));
    }
}

} // namespace gonio
