#pragma once
// The Gaussian distribution of angles [M18 Eq. 14]: D(m) = C exp(-theta_m^2 / (2 sigma^2)) /
// cos theta_m, sigma in radians, isotropic, with 1/C = 2 pi int_0^{pi/2} exp(-theta^2 /
// (2 sigma^2)) sin theta dtheta computed numerically (to 1e-13). As a radial slope density it
// takes Lambda and its samplers from RadialNdf.
#include "heightfield/ndf/radial_ndf.h"

namespace gonio {

class GaussianAngles final : public RadialNdf {
  public:
    static constexpr double kSigmaMin = 1e-3, kSigmaMax = 1.5; // radians
    explicit GaussianAngles(double sigma);
    double sigma() const { return sigma_; }
    // 1/C by quadrature, and its small-sigma series 2 pi sigma^2 (1 - sigma^2/3 + sigma^4/15 -
    // sigma^6/105) (term by term from sin's series; the cut at pi/2 is negligible below ~0.4).
    static double inverse_normalisation(double sigma);
    static double inverse_normalisation_series(double sigma);

  private:
    double sigma_;
};

} // namespace gonio
