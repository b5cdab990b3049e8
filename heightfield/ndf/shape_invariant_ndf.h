#pragma once
// Shape-invariant anisotropic distributions: D(m) = P22(slope) / cos^4(theta_m) with
// P22(p, q) = P22_1(p / alpha_x, q / alpha_y) / (alpha_x alpha_y) [R19 Eq. 6, footnote 1], where
// P22_1 is an isotropic slope density of unit roughness. Stretching the slopes turns Lambda and the
// visible-normal sampling of any alpha into those of alpha = 1 (Heitz 2014 section 5.3;
// Heitz & d'Eon 2014, "Importance sampling microfacet-based BSDFs using the distribution of
// visible normals", section 4).
#include "heightfield/ndf/ndf.h"

namespace gonio {

class ShapeInvariantNdf : public Ndf {
  public:
    // alpha_x, alpha_y > 0: the usual Beckmann/GGX roughness along x and y (docs/configuration.md: alpha).
    ShapeInvariantNdf(double alpha_x, double alpha_y);

    double alpha_x() const { return ax_; }
    double alpha_y() const { return ay_; }

    double D(const Vec3& m) const final;
    double lambda(const Vec3& v) const final;
    Vec3 sample_m(double u1, double u2) const final;
    Vec3 sample_visible(const Vec3& v, double u1, double u2) const override;
    std::string describe() const override;
    double narrowest_feature() const override;
    double widest_feature() const override;
    bool slope_stretch(double& alpha_x, double& alpha_y) const final {
        alpha_x = ax_, alpha_y = ay_;
        return true;
    }

  protected:
    // Unit-roughness isotropic model, in terms of the squared stretched slope
    // r2 = (p/alpha_x)^2 + (q/alpha_y)^2 and, for D, of cos^2(theta_m):
    // D(m) = d_unit(r2, cos2) / (alpha_x alpha_y)  with  d_unit = P22_1(r2) / cos^4.
    virtual double d_unit(double r2, double cos2) const = 0;
    // Lambda of unit roughness as a function of t2 = tan^2(theta) (already stretched).
    virtual double lambda_unit(double t2) const = 0;
    // Squared radius of a slope drawn from P22_1 (radial inverse CDF), u in [0, 1).
    virtual double sample_slope_radius2(double u) const = 0;
    // Slopes (x, y) of a unit-roughness facet visible from a direction at polar angle theta with
    // cos_theta = c (azimuth 0), pdf proportional to max(0, cot(theta) - x) P22_1(x, y).
    virtual void sample_visible_slope(double c, double u1, double u2, double& x,
                                      double& y) const = 0;

  private:
    double ax_, ay_;
};

} // namespace gonio
