#pragma once
// Anisotropic GGX (Trowbridge-Reitz) distribution [M18 Eq. 21; R19 section 2.1]:
//   D(m) = 1 / (pi ax ay cos^4 theta_m (1 + tan^2 theta_m (cos^2 phi_m/ax^2 + sin^2
//   phi_m/ay^2))^2),
// with its exact Smith Lambda [M18 Eq. 22]. (M18 Eq. 21 prints sigma_x and sigma_y swapped; the
// form above is the one that matches Eq. 22 and Walter et al. 2007.) Its slope variance is
// infinite.
#include "heightfield/ndf/shape_invariant_ndf.h"

namespace gonio {

class Ggx final : public ShapeInvariantNdf {
  public:
    Ggx(double alpha_x, double alpha_y) : ShapeInvariantNdf(alpha_x, alpha_y) {}
    explicit Ggx(double alpha) : Ggx(alpha, alpha) {}
    std::string name() const override { return "ggx"; }

  protected:
    double d_unit(double r2, double cos2) const override;
    double lambda_unit(double t2) const override;
    double sample_slope_radius2(double u) const override;
    void sample_visible_slope(double c, double u1, double u2, double& x, double& y) const override;
};

} // namespace gonio
