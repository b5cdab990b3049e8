#include "heightfield/ndf/ggx.h"

#include "heightfield/ndf/ndf_family.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gonio {

double Ggx::d_unit(double r2, double cos2) const {
    const double k = cos2 + cos2 * r2; // cos^2 (1 + tan^2): stays finite at the horizon
    return 1.0 / (kPi * k * k);        // M18 Eq. 21 with alpha = 1
}

double Ggx::lambda_unit(double t2) const {
    if (std::isinf(t2)) return std::numeric_limits<double>::infinity();
    // M18 Eq. 22, (-1 + sqrt(1 + 1/a^2)) / 2 with 1/a^2 = t2, rewritten without cancellation.
    return t2 / (2.0 * (1.0 + std::sqrt(1.0 + t2)));
}

double Ggx::sample_slope_radius2(double u) const {
    return u / (1.0 - u); // M18 Eq. 31: tan^2 theta = xi / (1 - xi)
}

void Ggx::sample_visible_slope(double c, double u1, double u2, double& x, double& y) const {
    // Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), Listing 1, at
    // unit roughness with the view (sin t, 0, cos t): exact, and stable at grazing angles.
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const Vec3 v{s, 0.0, c};
    const Vec3 t1{0.0, 1.0, 0.0};
    const Vec3 t2 = cross(v, t1);
    const double r = std::sqrt(u1), phi = kTwoPi * u2;
    const double p1 = r * std::cos(phi);
    const double h = 0.5 * (1.0 + c);
    const double p2 = (1.0 - h) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + h * r * std::sin(phi);
    const Vec3 n = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * v;
    const double nz = std::max(n.z, 1e-300);
    x = -n.x / nz;
    y = -n.y / nz;
}

} // namespace gonio

namespace gonio {
const NdfFamily& ggx_family() {
    static const NdfFamily f{"ggx", "GGX (Trowbridge-Reitz) [R19 section 2.1]", roughness_keys(),
                             [](TableReader& r, int) -> std::unique_ptr<Ndf> {
                                 const Roughness a = read_roughness(r);
                                 return std::make_unique<Ggx>(a.x, a.y);
                             },
                             true};
    return f;
}
} // namespace gonio
