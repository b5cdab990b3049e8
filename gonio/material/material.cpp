#include "gonio/material/material.h"

#include "gonio/material/fresnel.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gonio {

bool SpecularReflector::scatter(const Vec3& wi, const Vec3& m, Rng&, Vec3& wo,
                                double* weight) const {
    const double c = dot(wi, m);
    wo = reflect(wi, m);
    fresnel_.scale(std::abs(c), weight); // (F = 1 for a perfect mirror)
    return true;
}

Vec3 cosine_direction(const Vec3& m, Rng& rng) {
    // Malley's method in an orthonormal frame of m (Duff et al. 2017, "Building an Orthonormal
    // Basis, Revisited").
    const double sign = std::copysign(1.0, m.z);
    const double a = -1.0 / (sign + m.z), b = m.x * m.y * a;
    const Vec3 t{1.0 + sign * m.x * m.x * a, sign * b, -sign * m.x};
    const Vec3 u{b, sign + m.y * m.y * a, -m.y};
    const double r = std::sqrt(rng.uniform()), phi = kTwoPi * rng.uniform();
    const double x = r * std::cos(phi), y = r * std::sin(phi),
                 z = std::sqrt(std::max(0.0, 1 - r * r));
    return normalize(x * t + y * u + z * m);
}

bool LambertianFacet::scatter(const Vec3&, const Vec3& m, Rng& rng, Vec3& wo,
                              double* weight) const {
    wo = cosine_direction(m, rng);
    for (int k = 0; k < channels(); ++k) weight[k] *= albedo_[k];
    return true;
}

bool refract(const Vec3& wi, const Vec3& n, double eta, Vec3& wt) {
    // Snell's law in vector form (Walter et al. 2007, Eq. 40, with eta = n_t / n_i).
    const double cos_i = dot(wi, n);
    const double sin2_t = std::max(0.0, 1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) return false;
    const double cos_t = std::sqrt(1.0 - sin2_t);
    wt = normalize((-1.0 / eta) * wi + (cos_i / eta - cos_t) * n);
    return true;
}

bool DielectricFacet::scatter(const Vec3& wi, const Vec3& m, Rng& rng, Vec3& wo, double*) const {
    // From below, the interface is seen with the normal -m and the relative index 1 / eta.
    const bool above = dot(wi, m) >= 0;
    const Vec3 n = above ? m : -m;
    const double eta = above ? eta_ : 1.0 / eta_;
    const double F = fresnel_dielectric(std::abs(dot(wi, m)), eta); // M18 Eq. 8; 1 under TIR
    if (rng.uniform() < F || !refract(wi, n, eta, wo)) wo = reflect(wi, m);
    return true;
}

} // namespace gonio
