#pragma once
// The rough interfaced Lambertian BRDF of M18 section 3.2, single scattering between microfacets:
// f = f_s + f_b [M18 Eq. 12]. f_s is the specular microfacet BRDF with the interface's Fresnel
// reflectance [M18 Eq. 4, 8]; f_b integrates the facets' body reflection [M18 Eq. 9] over the
// distribution [M18 Eq. 13]:
//   f_b = K_d / (pi n^2 (1 - r_i K_d)) int T(i, m) T(o, m) D(m) G(i, o, m) |i.m||o.m| /
//   (|i.n||o.n|) dm.
// G is Smith's (height-correlated or not) or Torrance-Sparrow's V-cavity term [M18 Eq. 15-22],
// and D any gonio NDF (M18 Table 2's Gaussian, Beckmann and GGX among them). At n = 1 this is the
// Lambertian-microfacet BRDF; as the roughness vanishes, the flat interfaced Lambertian surface.
//
// The integral over m is a tensor Gauss-Legendre rule in the NDF sampler's primary space
// (m = sample_m(u1, u2), pdf D(m) m.n), so its nodes follow D however narrow it is; for samplers
// that are not continuous maps (tables, mixtures, blends) a composite rule in (theta, phi).
#include "gonio/material/interfaced_lambertian.h"
#include "gonio/model/microfacet_model.h"

#include <vector>

namespace gonio {

class InterfacedLambertianModel final : public BrdfModel {
  public:
    // eta and albedo as for InterfacedLambertianFacet (one value, or one per channel);
    // `body_points` Gauss-Legendre nodes per axis of the body integral. Keeps a reference to ndf.
    InterfacedLambertianModel(const Ndf& ndf, std::vector<double> eta, std::vector<double> albedo,
                              MaskingForm masking, int body_points = 32);

    InterfacedLambertianModel(const InterfacedLambertianModel&) = delete; // body_ points here
    InterfacedLambertianModel& operator=(const InterfacedLambertianModel&) = delete;
    int channels() const override { return facet_.channels(); }
    void eval_cosine(const Vec3& i, const Vec3& o, double* out) const override;
    double narrowest_feature() const override { return specular_.narrowest_feature(); }
    double widest_feature() const override { return specular_.widest_feature(); }
    // f_s and f_b apart: only f_s has a lobe, and f_b costs body_points^2 evaluations.
    std::vector<const BrdfModel*> terms() const override { return {&specular_, &body_}; }

    // The two parts separately, times cos(theta_o), per channel.
    void specular_cosine(const Vec3& i, const Vec3& o, double* out) const;
    void body_cosine(const Vec3& i, const Vec3& o, double* out) const;
    const InterfacedLambertianFacet& facet() const { return facet_; }

  private:
    // f_b as a model of its own: smooth, no lobe.
    struct Body final : BrdfModel {
        const InterfacedLambertianModel* owner;
        explicit Body(const InterfacedLambertianModel* o) : owner(o) {}
        int channels() const override { return owner->channels(); }
        void eval_cosine(const Vec3& i, const Vec3& o, double* out) const override {
            owner->body_cosine(i, o, out);
        }
        double narrowest_feature() const override { return INFINITY; }
        double widest_feature() const override { return INFINITY; }
    };

    const Ndf& ndf_;
    InterfacedLambertianFacet facet_;
    MicrofacetModel specular_;
    MaskingForm masking_;
    std::vector<Vec3> nodes_;     // m
    std::vector<double> weights_; // Gauss-Legendre weight / (m.n): int g D dm = sum w g(m)
    Body body_{this};
};

} // namespace gonio
