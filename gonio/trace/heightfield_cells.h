#pragma once
// The cell arithmetic of the height-field walk (heightfield_traversal.h), shared by its scalar
// walk (heightfield_walk.inc) and its ray-parallel one (heightfield_lanes.cpp) so that both
// place a ray in the same cell and leap the same clear stretches, operation for operation.
// Included only by files built without FMA contraction (the edge functions' antisymmetry).
#include "core/math.h"

#include <algorithm>
#include <cmath>

namespace gonio::walk_cells {

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

// Where a walk stands: its distance along the ray, its origin moved by whole periods (the copy of
// the patch it is in), its cell and the side walls it crossed.
struct WalkPosition {
    double t, ox, oy;
    int cx, cy, wraps;
};

// On to t_new over a stretch clear of the surface, which may cross side walls (a grazing beam's
// entry many): 0, or 1 when the ray (origin height oz, direction d) left through its plane on
// the way (z > z_top going up, z < z_bottom going down; only the walls crossed before it count),
// 2 when past max_wraps walls.
[[gnu::always_inline]] inline int leap(WalkPosition& p, double t_new, double oz, const Vec3& d,
                                       double inv_dx, double inv_dy, double inv_dz, double z_top,
                                       double z_bottom, int max_wraps, const double* line, int n,
                                       double inv_spacing) {
    const double period = line[n];
    const double z_stop = d.z > 0 ? z_top : z_bottom, stop_sign = d.z > 0 ? 1 : d.z < 0 ? -1 : 0;
    p.t = t_new;
    const int wraps_before = p.wraps;
    const bool out = (oz + p.t * d.z - z_stop) * stop_sign > 0;
    const double plane_t = out ? ((d.z > 0 ? z_top : z_bottom) - oz) * inv_dz : 0.0;
    int walls_before_plane = 0;
    double px = p.ox + p.t * d.x, py = p.oy + p.t * d.y;
    while (px > period || (px == period && !(d.x < 0)) || px < 0 || (px == 0 && d.x < 0)) {
        const bool over = px >= period;
        walls_before_plane += out && ((over ? period : 0.0) - p.ox) * inv_dx < plane_t;
        px += over ? -period : period, p.ox += over ? -period : period;
        ++p.wraps;
    }
    while (py > period || (py == period && !(d.y < 0)) || py < 0 || (py == 0 && d.y < 0)) {
        const bool over = py >= period;
        walls_before_plane += out && ((over ? period : 0.0) - p.oy) * inv_dy < plane_t;
        py += over ? -period : period, p.oy += over ? -period : period;
        ++p.wraps;
    }
    if (out) {
        p.wraps = wraps_before + walls_before_plane;
        return 1;
    }
    if (p.wraps > max_wraps) return 2;
    p.cx = cell_of(px, d.x, line, n, inv_spacing);
    p.cy = cell_of(py, d.y, line, n, inv_spacing);
    return 0;
}

} // namespace gonio::walk_cells
