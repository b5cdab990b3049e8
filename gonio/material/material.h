#pragma once
// What one microfacet does to a ray, per spectral channel. Directions point away from the facet:
// `wi` towards where the ray came from, the returned direction where it goes next.
// Implemented here: specular reflectors (perfect mirror, conductor, Schlick). Dielectrics with
// transmission, Lambertian and interfaced Lambertian facets plug in behind the same interface.
#include "core/math.h"
#include "core/random.h"
#include "gonio/material/fresnel_term.h"

#include <vector>

namespace gonio {

class Material {
  public:
    virtual ~Material() = default;
    virtual int channels() const = 0;
    // Scatters at a facet of unit normal m; multiplies weight[0..channels) by the throughput.
    // Returns false if the ray ends at this facet (absorbed).
    virtual bool scatter(const Vec3& wi, const Vec3& m, Rng& rng, Vec3& wo,
                         double* weight) const = 0;
};

// Mirror reflection about the facet, weighted by its Fresnel reflectance per channel.
class SpecularReflector final : public Material {
  public:
    explicit SpecularReflector(FresnelTerm fresnel) : fresnel_(std::move(fresnel)) {}
    int channels() const override { return fresnel_.channels(); }
    bool scatter(const Vec3& wi, const Vec3& m, Rng& rng, Vec3& wo, double* weight) const override;

  private:
    FresnelTerm fresnel_;
};

// A Lambertian facet: the ray leaves in a cosine-distributed direction about the facet normal,
// weighted by the albedo per channel (the facet BRDF albedo / pi, importance-sampled).
class LambertianFacet final : public Material {
  public:
    explicit LambertianFacet(std::vector<double> albedo) : albedo_(std::move(albedo)) {}
    int channels() const override { return int(albedo_.size()); }
    bool scatter(const Vec3& wi, const Vec3& m, Rng& rng, Vec3& wo, double* weight) const override;

  private:
    std::vector<double> albedo_;
};

} // namespace gonio
