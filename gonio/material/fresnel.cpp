#include "gonio/material/fresnel.h"

#include <algorithm>
#include <cmath>

namespace gonio {

double fresnel_dielectric(double cos_i, double eta) {
    if (cos_i < 0) {
        cos_i = -cos_i;
        eta = 1.0 / eta;
    }
    cos_i = std::min(cos_i, 1.0);
    if (eta == 1.0) return 0.0;
    const double c = cos_i;
    const double g2 = eta * eta + c * c - 1.0;
    if (g2 <= 0) return 1.0; // total internal reflection
    const double g = std::sqrt(g2);
    if (g + c == 0) return 1.0;
    // M18 Eq. 8
    const double a = (g - c) / (g + c);
    const double b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return std::min(1.0, 0.5 * a * a * (1.0 + b * b));
}

double fresnel_conductor(double cos_i, std::complex<double> eta) {
    // Real arithmetic: the reflectance of the s and p amplitudes of a complex cos_t, without
    // complex division (a library call each, several times slower).
    const double c = std::clamp(cos_i, 0.0, 1.0);
    if (c == 0.0) return 1.0; // grazing: every conductor reflects all
    const double n = eta.real(), k = eta.imag();
    return fresnel_conductor(c, 1.0 - c * c, n * n - k * k, 4.0 * n * n * k * k);
}

double fresnel_schlick(double cos_i, double f0) {
    const double m = 1.0 - std::clamp(cos_i, 0.0, 1.0);
    const double m2 = m * m;
    return f0 + (1.0 - f0) * m2 * m2 * m;
}

double fresnel_f0(double eta) {
    const double r = (eta - 1.0) / (eta + 1.0);
    return r * r;
}

} // namespace gonio
