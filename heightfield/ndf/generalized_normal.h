#pragma once
// Generalised normal distribution of slopes (GND) [R19 section 2.1, Fig. 3; Holzschuch &
// Pacanowski 2017]:
//   P22(s) = p / (2 pi alpha^2 Gamma(2/p)) exp(-(|s| / alpha)^p),
// anisotropic by stretching the slope axes. p = 2 is Beckmann; p < 2 is peaked with heavier
// tails, p > 2 flat-topped. gonio accepts p in [0.5, 20].
#include "heightfield/ndf/radial_ndf.h"

namespace gonio {

class GeneralizedNormal final : public RadialNdf {
  public:
    static constexpr double kPMin = 0.5, kPMax = 20;
    GeneralizedNormal(double alpha_x, double alpha_y, double p);
    double p() const { return p_; }

  private:
    double p_;
};

} // namespace gonio
