#include "heightfield/constraint_geometry.h"

#include "core/check.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

HeightField constraint_geometry(Constraint kind, int n, int lattice, double relief) {
    // surface.constraint and surface.lattice, checked where [surface] is read.
    GONIO_CHECK(kind != Constraint::none && lattice >= 1 && lattice <= n / 2);
    HeightField s(n, 1.0);
    const double period = double(n) / lattice, radius = 0.4 * period;
    const double sign = kind == Constraint::domes ? 1.0 : -1.0;
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            // Offset from the nearest feature centre (centres at (k + 1/2) period).
            const double dx = std::fmod(x + 0.5, period) - 0.5 * period;
            const double dy = std::fmod(y + 0.5, period) - 0.5 * period;
            const double r2 = (dx * dx + dy * dy) / (radius * radius);
            s.h[size_t(y) * n + x] = r2 < 1 ? float(sign * relief * radius * (1 - r2)) : 0.0f;
        }
    }
    return s;
}

} // namespace gonio
