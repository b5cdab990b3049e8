#pragma once
// Anisotropic Beckmann distribution [M18 Eq. 16; R19 section 2.1]:
//   D(m) = exp(-tan^2 theta_m (cos^2 phi_m / ax^2 + sin^2 phi_m / ay^2)) / (pi ax ay cos^4
//   theta_m),
// with its exact Smith Lambda [M18 Eq. 20]. The slope standard deviation per axis is alpha /
// sqrt 2.
#include "heightfield/ndf/shape_invariant_ndf.h"

namespace gonio {

class Beckmann final : public ShapeInvariantNdf {
  public:
    Beckmann(double alpha_x, double alpha_y) : ShapeInvariantNdf(alpha_x, alpha_y) {}
    explicit Beckmann(double alpha) : Beckmann(alpha, alpha) {}
    std::string name() const override { return "beckmann"; }
    bool gaussian_slopes(double& ax, double& ay) const override { return slope_stretch(ax, ay); }

  protected:
    double d_unit(double r2, double cos2) const override;
    double lambda_unit(double t2) const override;
    double sample_slope_radius2(double u) const override;
    void sample_visible_slope(double c, double u1, double u2, double& x, double& y) const override;
};

} // namespace gonio
