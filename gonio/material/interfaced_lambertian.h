#pragma once
// The interfaced Lambertian microfacet of M18 section 3.1: a smooth dielectric interface of
// relative index n_i = n1 / n0 >= 1 over a Lambertian substrate of reflectance K_d. At a facet the
// light is reflected specularly with the Fresnel reflectance F [M18 Eq. 8], or transmitted,
// scattered by the substrate and reflected between substrate and interface, and leaves through the
// interface: f_b = T(i, m) T(o, m) K_d / (pi n_i^2 (1 - K_d r_i))  [M18 Eq. 9], with r_i the
// interface's internal diffuse reflectance from n_i^2 (1 - r_i) = 1 - r_e [M18 Eq. 10-11].
//
// Sampling: specular with probability max over channels of F; otherwise the exit direction with
// density T(o, m) cos / (pi (1 - r_e)) for channel 0 (cosine sampling, accepted with T), so that
// with one channel and K_d = 1 every ray keeps weight 1 exactly (the material conserves energy ray
// by ray); other channels are weighted by their ratio to it. Per channel: K_d and n_i.
#include "gonio/material/material.h"

#include <vector>

namespace gonio {

class InterfacedLambertianFacet final : public Material {
  public:
    // eta (n_i >= 1) and albedo (K_d in [0, 1]): one value each, or one per channel (a single value
    // applies to every channel). Throws std::invalid_argument otherwise.
    InterfacedLambertianFacet(std::vector<double> eta, std::vector<double> albedo);
    int channels() const override { return int(eta_.size()); }
    const std::vector<double>& eta() const { return eta_; } // n_i per channel
    bool scatter(const Vec3& wi, const Vec3& m, Rng& rng, Vec3& wo, double* weight) const override;

    // The body BRDF of a facet [M18 Eq. 9], for channel k (i and o above the facet).
    double body_brdf(const Vec3& i, const Vec3& o, const Vec3& m, int k) const;
    // The facet's directional albedo from i: F(i) + T(i) K_d (1 - r_i) / (1 - K_d r_i).
    double albedo(const Vec3& i, const Vec3& m, int k) const;
    double external_diffuse_reflectance(int k) const { return re_[k]; }
    double internal_diffuse_reflectance(int k) const { return ri_[k]; }

    // r_e of a flat interface lit by a Lambertian source from outside: int F sin(2 theta) dtheta
    // [M18 Eq. 10 form], by quadrature (any n_i >= 1, including 1); and Molenaar's closed form
    // [M18 Eq. 11] (n_i > 1), which the tests compare with it.
    static double diffuse_reflectance(double eta);
    static double molenaar_reflectance(double eta);

  private:
    std::vector<double> eta_, kd_, re_, ri_;
};

} // namespace gonio
