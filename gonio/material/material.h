#pragma once
// What one microfacet does to a ray, per spectral channel. Directions point away from the facet:
// `wi` towards where the ray came from, the returned direction where it goes next.
// Implemented here: specular reflectors (perfect mirror, conductor, Schlick), dielectric
// facets with transmission, Lambertian facets; interfaced Lambertian facets in
// interfaced_lambertian.h. The facet normal m always faces the upper side (+z); a ray may meet it
// from below only inside a transmissive material (wi.m < 0).
#include "core/math.h"
#include "core/random.h"
#include "gonio/material/fresnel_term.h"

#include <vector>

namespace gonio {

class Material {
  public:
    virtual ~Material() = default;
    virtual int channels() const = 0;
    // Scatters at a facet of unit normal m into the unit direction wo; multiplies
    // weight[0..channels) by the throughput. Returns false if the ray ends at this facet
    // (absorbed).
    virtual bool scatter(const Vec3& wi, const Vec3& m, Rng& rng, Vec3& wo,
                         double* weight) const = 0;
    // True if rays may cross the surface (then the lower sensor and transmitted orders exist).
    virtual bool transmits() const { return false; }
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

// A smooth dielectric interface of real relative index eta = n_below / n_above, one channel:
// reflection with the exact Fresnel probability [M18 Eq. 8], otherwise refraction by Snell's law.
// The choice is stochastic, so the ray's weight is unchanged and R + T = 1 holds ray by ray. The
// weight is power, not radiance: no eta^2 factor on refraction. A ray inside the material meets
// facets from below (wi.m < 0), where the relative index is 1 / eta and total internal
// reflection can occur.
class DielectricFacet final : public Material {
  public:
    explicit DielectricFacet(double eta) : eta_(eta) {}
    int channels() const override { return 1; }
    bool transmits() const override { return true; }
    bool scatter(const Vec3& wi, const Vec3& m, Rng& rng, Vec3& wo, double* weight) const override;

  private:
    double eta_;
};

// A cosine-distributed direction about the unit normal m (Malley's method), from two uniforms of
// rng: the Lambertian facet's exit, shared by every diffuse material.
Vec3 cosine_direction(const Vec3& m, Rng& rng);

// Refraction of wi (pointing away from the interface, on the side of n) through an interface of
// relative index eta = n_transmitted / n_incident. Returns false on total internal reflection.
bool refract(const Vec3& wi, const Vec3& n, double eta, Vec3& wt);

} // namespace gonio
