#pragma once
// Cubic (Catmull-Rom) interpolation of samples on a uniform grid, used by every tabulated Lambda.
// The ghost samples beyond the ends are extrapolated quadratically, so the end intervals keep a
// third-order error (clamped ghosts would drop it to first order in the slope).
#include <algorithm>
#include <vector>

namespace gonio {

// v sampled at x = 0, 1, ..., v.size() - 1 (at least two samples); x is clamped to that range.
inline double catmull_rom(const std::vector<double>& v, double x) {
    const int last = static_cast<int>(v.size()) - 1;
    x = std::clamp(x, 0.0, double(last));
    const int i = std::min(static_cast<int>(x), last - 1);
    const double t = x - i;
    auto at = [&](int k) {
        if (last >= 2 && k < 0) return 3 * v[0] - 3 * v[1] + v[2];
        if (last >= 2 && k > last) return 3 * v[last] - 3 * v[last - 1] + v[last - 2];
        return v[std::clamp(k, 0, last)];
    };
    const double p0 = at(i - 1), p1 = at(i), p2 = at(i + 1), p3 = at(i + 2);
    return p1 + 0.5 * t *
                    (p2 - p0 + t * (2 * p0 - 5 * p1 + 4 * p2 - p3 + t * (3 * (p1 - p2) + p3 - p0)));
}

} // namespace gonio
