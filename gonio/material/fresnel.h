#pragma once
// Fresnel reflectance of a smooth interface, unpolarised light.
#include <algorithm>
#include <cmath>
#include <complex>

namespace gonio {

// Dielectric reflectance [M18 Eq. 8] for cos_i = i.m and eta = n_transmitted / n_incident
// (> 0). A negative cos_i means the light arrives from the other side: eta is then inverted.
// Total internal reflection gives 1. eta = 1 gives 0 (no interface).
double fresnel_dielectric(double cos_i, double eta);

// Conductor reflectance for a complex relative index eta = n + i k (k >= 0), cos_i in [0, 1]
// (Born & Wolf, Principles of Optics, section 14.2; the s and p amplitudes with a complex
// refraction angle). With k = 0 it equals fresnel_dielectric.
double fresnel_conductor(double cos_i, std::complex<double> eta);

// The same from what the index alone decides, u0 = n^2 - k^2 and w = 4 n^2 k^2, for c = cos_i in
// (0, 1] and s2 = 1 - c^2: inline and branch-free, so that a loop over channels vectorises.
inline double fresnel_conductor(double c, double s2, double u0, double w) {
    // Born & Wolf, section 14.2: n^2 - sin^2 = (a + i b)^2 with a^2, b^2 = (|.| +- u) / 2.
    const double u = u0 - s2, root = std::sqrt(u * u + w);
    const double a2 = std::max(0.0, 0.5 * (root + u)), b2 = std::max(0.0, 0.5 * (root - u)),
                 a = std::sqrt(a2);
    const double ab = a2 + b2; // |n^2 - sin^2|
    // Rs = ps / qs; Rp / Rs = pp / qp, with sin(theta) tan(theta) = s2 / c times c^2 above and
    // below (finite at grazing); (Rs + Rp) / 2 over one division.
    const double ps = ab - 2.0 * a * c + c * c, qs = ab + 2.0 * a * c + c * c;
    const double pp = ab * c * c - 2.0 * a * s2 * c + s2 * s2,
                 qp = ab * c * c + 2.0 * a * s2 * c + s2 * s2;
    return std::min(1.0, 0.5 * ps * (qp + pp) / (qs * qp));
}

// Schlick's approximation F0 + (1 - F0) (1 - cos_i)^5 (Schlick 1994, Eq. 24).
double fresnel_schlick(double cos_i, double f0);

// Normal-incidence reflectance of a dielectric: ((eta - 1) / (eta + 1))^2.
double fresnel_f0(double eta);

} // namespace gonio
