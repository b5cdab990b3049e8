#pragma once
// Fresnel reflectance of a smooth interface, unpolarised light.
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

// Schlick's approximation F0 + (1 - F0) (1 - cos_i)^5 (Schlick 1994, Eq. 24).
double fresnel_schlick(double cos_i, double f0);

// Normal-incidence reflectance of a dielectric: ((eta - 1) / (eta + 1))^2.
double fresnel_f0(double eta);

} // namespace gonio
