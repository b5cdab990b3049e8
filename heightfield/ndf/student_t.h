#pragma once
// Student's t distribution of slopes (STD) [R19 section 2.1, Fig. 3]:
//   P22(s) = (1 / (pi alpha^2)) (1 + |s|^2 / ((gamma - 1) alpha^2))^(-gamma),
// anisotropic by stretching the slope axes. gamma = 2 is GGX; gamma -> infinity is Beckmann;
// smaller gamma gives heavier tails. D(m) ~ tan^(4 - 2 gamma) theta_m near the horizon: it
// diverges there for gamma < 2 (and Lambda is infinite for gamma <= 3/2). gonio accepts gamma in
// [2, 1e6], where D is bounded and every integral it needs is smooth.
#include "heightfield/ndf/radial_ndf.h"

namespace gonio {

class StudentT final : public RadialNdf {
  public:
    static constexpr double kGammaMin = 2, kGammaMax = 1e6;
    StudentT(double alpha_x, double alpha_y, double gamma);
    double gamma() const { return gamma_; }

  private:
    double gamma_;
};

} // namespace gonio
