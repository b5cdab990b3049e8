#include "gonio/trace/backend_comparison.h"

#include "core/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>

namespace gonio {

namespace {
// Whether grid point (gx, gy) lies in triangle t of cell (cx, cy), within `slack` cells (the
// point's rounding): the patch repeats, so the cell is taken modulo n.
bool in_triangle(double gx, double gy, int n, int cx, int cy, int t, double slack) {
    double u = gx - cx, v = gy - cy;
    u -= std::round(u / n) * n, v -= std::round(v / n) * n; // the nearest copy of the cell
    if (t == 0) return u >= -slack && v >= -slack && u + v <= 1 + slack;
    return u <= 1 + slack && v <= 1 + slack && u + v >= 1 - slack;
}

// The ray (o, d) against triangle t of cell (i, j), exactly enough (long double, from the float
// vertices): its t and its smallest barycentric coordinate (negative: the ray passes outside).
struct Exact {
    long double t, inside;
};
Exact exact_hit(const Scene& scene, const float* s, int i, int j, int t) {
    using V = long double;
    const Vec3 p[4] = {scene.vertex(i, j), scene.vertex(i + 1, j), scene.vertex(i + 1, j + 1),
                       scene.vertex(i, j + 1)};
    const Vec3& a = t == 0 ? p[0] : p[2];
    const Vec3& b = t == 0 ? p[1] : p[3];
    const Vec3& c = t == 0 ? p[3] : p[1];
    const V o[3] = {s[0], s[1], s[2]}, d[3] = {s[3], s[4], s[5]};
    const V e1[3] = {V(b.x) - a.x, V(b.y) - a.y, V(b.z) - a.z};
    const V e2[3] = {V(c.x) - a.x, V(c.y) - a.y, V(c.z) - a.z};
    const V pv[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2],
                     d[0] * e2[1] - d[1] * e2[0]};
    const V det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    const V tv[3] = {o[0] - a.x, o[1] - a.y, o[2] - a.z};
    const V qv[3] = {tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2],
                     tv[0] * e1[1] - tv[1] * e1[0]};
    const V u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
    const V v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
    const V tt = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
    return {tt, std::min({u, v, 1 - u - v})};
}

std::string describe(const char* what, const float* s, const SegmentHit& a, const SegmentHit& b) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "%s: o (%.9g %.9g %.9g) d (%.9g %.9g %.9g): reference t %.9g cell (%d %d) tri %d,"
                  " other t %.9g cell (%d %d) tri %d",
                  what, s[0], s[1], s[2], s[3], s[4], s[5], a.t, a.cell_x, a.cell_y, a.triangle,
                  b.t, b.cell_x, b.cell_y, b.triangle);
    return line;
}
} // namespace

void BackendComparison::add(const BackendComparison& o) {
    segments += o.segments, both_missed += o.both_missed, agree += o.agree;
    on_shared_edge += o.on_shared_edge, only_reference += o.only_reference;
    only_other += o.only_other, other_triangle += o.other_triangle, t_differs += o.t_differs;
    reference_rounding += o.reference_rounding;
    max_t_relative = std::max(max_t_relative, o.max_t_relative);
    for (const std::string& e : o.examples)
        if (examples.size() < 20) examples.push_back(e);
}

BackendComparison compare_backends(const Scene& reference, const Scene& other,
                                   const std::vector<float>& segments, double t_tolerance,
                                   std::size_t first, std::size_t last) {
    last = std::min(last, segments.size() / 6);
    tbb::combinable<BackendComparison> parts;
    parallel_for_ranges<std::size_t>(
        first, std::max(first, last), 4096, [&](const tbb::blocked_range<std::size_t>& range) {
            BackendComparison& c = parts.local();
            for (std::size_t k = range.begin(); k < range.end(); ++k) {
                const float* s = &segments[6 * k];
                const SegmentHit a = reference.intersect(s, s + 3);
                const SegmentHit b = other.intersect(s, s + 3);
                ++c.segments;
                const bool ha = std::isfinite(a.t), hb = std::isfinite(b.t);
                std::string what;
                if (!ha && !hb) {
                    ++c.both_missed;
                    continue;
                }
                // Where the two disagree, the exact test decides whether Embree's float arithmetic
                // (its inside / outside call on a crease the ray grazes, or its t on a short
                // segment) is what differs: then the traversal agrees with the exact answer.
                auto exact = [&](const SegmentHit& h) {
                    return exact_hit(other, s, h.cell_x, h.cell_y, h.triangle);
                };
                if (ha && !hb) {
                    if (exact(a).inside < 0) {
                        ++c.reference_rounding;
                        continue;
                    }
                    ++c.only_reference, what = "only the reference hit";
                } else if (!ha && hb) {
                    if (exact(b).inside >= 0) {
                        ++c.reference_rounding;
                        continue;
                    }
                    ++c.only_other, what = "only the other hit";
                } else {
                    const int cells = reference.cells();
                    const double gx = a.point.x / reference.spacing(),
                                 gy = a.point.y / reference.spacing();
                    const bool same =
                        a.cell_x == b.cell_x && a.cell_y == b.cell_y && a.triangle == b.triangle;
                    // Embree's point is found from a float t: allow its rounding, in cells.
                    const double slack = 1e-4;
                    const bool shared =
                        !same && in_triangle(gx, gy, cells, b.cell_x, b.cell_y, b.triangle, slack);
                    const double rel = std::abs(a.t - b.t) / std::max(std::abs(a.t), 1e-30);
                    if (!same && !shared) {
                        const Exact ea = exact(a), eb = exact(b);
                        if (eb.inside >= 0 && (ea.inside < 0 || eb.t <= ea.t)) {
                            ++c.reference_rounding;
                            continue;
                        }
                        ++c.other_triangle, what = "on another triangle";
                    } else if (rel > t_tolerance) {
                        const long double t_exact = exact(b).t;
                        const double ref_err = double(std::abs((a.t - t_exact) / t_exact));
                        const double other_err = double(std::abs((b.t - t_exact) / t_exact));
                        if (other_err <= t_tolerance && ref_err > t_tolerance) {
                            ++c.reference_rounding;
                            continue;
                        }
                        ++c.t_differs, what = "t differs";
                    } else {
                        ++c.agree;
                        if (shared) ++c.on_shared_edge;
                        c.max_t_relative = std::max(c.max_t_relative, rel);
                        continue;
                    }
                }
                if (c.examples.size() < 20) c.examples.push_back(describe(what.c_str(), s, a, b));
            }
        });
    BackendComparison all;
    parts.combine_each([&](const BackendComparison& p) { all.add(p); });
    return all;
}

} // namespace gonio
