#pragma once
// The Gaussian distribution of angles [M18 Eq. 14]: D(m) = C exp(-theta_m^2 / (2 sigma^2)) /
// cos theta_m, sigma in radians, isotropic, for theta_m <= theta_max, with
// 1/C = 2 pi int_0^theta_max exp(-theta^2 / (2 sigma^2)) sin theta dtheta computed numerically (to
// 1e-13). As a radial slope density it takes Lambda and its samplers from RadialNdf.
//
// Why theta_max: the 1/cos makes Smith's projected area int <v.m> D dw diverge (logarithmically, in
// the facets at the horizon) for every v off the normal, so the untruncated M18 distribution has
// Lambda = infinity (M18 pairs it with Torrance-Sparrow's G, not Smith's). Cut at theta_max
// (default 89.9 deg) it is a proper distribution with a finite, exact Lambda; the cut's share of
// the mass is C exp(-theta_max^2 / 2 sigma^2) (pi/2 - theta_max) at most, and Lambda(v) grows like
// 2 C exp(-(pi/2)^2 / 2 sigma^2) tan theta_v ln(1 / (pi/2 - theta_max)) as the cut nears the
// horizon: negligible for sigma < 0.3, a modelling choice the user sees for rougher Gaussians.
#include "heightfield/ndf/radial_ndf.h"

namespace gonio {

class GaussianAngles final : public RadialNdf {
  public:
    // The keys' ranges, in degrees as configs give them (sigma: 0.001 to 1.5 rad).
    static constexpr double kSigmaMinDeg = 0.0573, kSigmaMaxDeg = 85.94;
    static constexpr double kThetaMaxDefault = 89.9 * kPi / 180;
    static constexpr double kThetaMaxMinDeg = 60, kThetaMaxMaxDeg = 89.999;
    explicit GaussianAngles(double sigma, double theta_max = kThetaMaxDefault);
    double sigma() const { return sigma_; }
    double theta_max() const { return theta_max_; }
    // 1/C by quadrature, and its small-sigma series 2 pi sigma^2 (1 - sigma^2/3 + sigma^4/15 -
    // sigma^6/105) (term by term from sin's series; the cut is negligible below sigma ~ 0.4).
    static double inverse_normalisation(double sigma, double theta_max = kThetaMaxDefault);
    static double inverse_normalisation_series(double sigma);

  private:
    double sigma_, theta_max_;
};

} // namespace gonio
