#pragma once
// Integrals over the hemisphere of normals (the NDF tests' brute force, and the tables of
// Ashikhmin's model): adaptive Gauss-Kronrod
// in (theta_m, phi_m), with theta split at multiples of the roughness (so narrow lobes are
// resolved) and at the horizon of a view direction (so the clamped dot product's kink is a
// piece boundary, not inside a piece).
#include "core/math.h"
#include "core/quadrature.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace gonio {

// Integral over the upper hemisphere of g(m) dw_m, g smooth except at the breakpoints.
// `scale` is the narrowest angular feature of g; `v`, if given, restricts the domain to v.m > 0
// (the great circle v.m = 0 becomes a piece boundary).
// `kinks`: polar angles where g is not smooth (the control points of a piecewise-linear NDF);
// `phi_kinks`: azimuths where it is not (the columns of a table).
inline double hemisphere_integral(const std::function<double(const Vec3&)>& g, double scale,
                                  const Vec3* v = nullptr, double tol = 1e-11,
                                  const std::vector<double>& kinks = {},
                                  const std::vector<double>& phi_kinks = {}) {
    std::vector<double> phi_breaks{0.0, kTwoPi};
    for (double p : phi_kinks)
        if (p > 0 && p < kTwoPi) phi_breaks.push_back(p);
    double phi_v = 0, sin_v = 0;
    if (v) {
        phi_v = spherical_phi(*v);
        sin_v = std::sqrt(std::max(0.0, 1 - v->z * v->z));
        for (double p : {phi_v + kPi / 2, phi_v + 3 * kPi / 2})
            phi_breaks.push_back(std::fmod(p, kTwoPi));
    }
    std::sort(phi_breaks.begin(), phi_breaks.end());
    auto over_theta = [&](double phi) {
        std::vector<double> breaks{0.0};
        for (double t = scale; t < kPi / 2; t *= 2) breaks.push_back(t);
        for (double t : kinks)
            if (t > 0 && t < kPi / 2) breaks.push_back(t);
        std::sort(breaks.begin(), breaks.end());
        double top = kPi / 2;
        if (v) { // v.m = sin t sin tv cos(p - pv) + cos t cos tv = 0
            const double c = sin_v * std::cos(phi - phi_v);
            if (c < 0) top = std::min(top, std::atan2(v->z, -c));
        }
        breaks.push_back(top);
        double sum = 0;
        for (size_t k = 0; k + 1 < breaks.size(); ++k) {
            const double a = breaks[k], b = std::min(breaks[k + 1], top);
            if (a >= top) break;
            if (b <= a) continue; // a break point given twice (a kink at a multiple of scale)
            sum += integrate_adaptive(
                [&](double t) { return g(spherical_direction(t, phi)) * std::sin(t); }, a, b, 1e-15,
                tol);
        }
        return sum;
    };
    double total = 0;
    for (size_t k = 0; k + 1 < phi_breaks.size(); ++k)
        total += integrate_adaptive(over_theta, phi_breaks[k], phi_breaks[k + 1], 1e-15, tol);
    return total;
}

} // namespace gonio
