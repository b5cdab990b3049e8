#pragma once
// The BSDFs a render shades with, in linear sRGB and in the local frame of the surface (n = +z):
// the tabulated BSDF of a simulated case (gonio/table) and an analytic Lambertian (the floor, and
// the reference the tests hold the table to). Directions point away from the surface: v towards the
// viewer, which is the table's incidence (Mitsuba's convention; the BSDF is reciprocal), l towards
// the light.
#include "gonio/render/environment.h"
#include "gonio/table/bsdf_table.h"

#include <memory>

namespace gonio {

class SurfaceBsdf {
  public:
    virtual ~SurfaceBsdf() = default;
    virtual Rgb eval(const Vec3& v, const Vec3& l) const = 0; // f in 1/sr, no cosine
    // l with pdf(v, l) (solid angle); false when nothing can be sampled.
    virtual bool sample(const Vec3& v, double u0, double u1, double u2, Vec3& l,
                        double& pdf) const = 0;
    virtual double pdf(const Vec3& v, const Vec3& l) const = 0;
};

class TableBsdf final : public SurfaceBsdf {
  public:
    explicit TableBsdf(std::shared_ptr<const BsdfTable> table); // a table of 3 channels (RGB)
    Rgb eval(const Vec3& v, const Vec3& l) const override;
    bool sample(const Vec3& v, double u0, double u1, double u2, Vec3& l,
                double& pdf) const override;
    double pdf(const Vec3& v, const Vec3& l) const override;

  private:
    std::shared_ptr<const BsdfTable> table_;
};

class LambertianBsdf final : public SurfaceBsdf {
  public:
    explicit LambertianBsdf(Rgb albedo) : albedo_(albedo) {}
    Rgb eval(const Vec3& v, const Vec3& l) const override;
    bool sample(const Vec3& v, double u0, double u1, double u2, Vec3& l,
                double& pdf) const override;
    double pdf(const Vec3& v, const Vec3& l) const override;

  private:
    Rgb albedo_;
};

// A table's channels as linear sRGB: one channel repeated, spectral channels through the CIE 1931
// observer under D65 (core/colour.h), negative (out-of-gamut) values clipped to 0; `clipped`
// counts them.
TableData to_linear_srgb(TableData d, const std::vector<double>& wavelengths_nm, long* clipped);

} // namespace gonio
