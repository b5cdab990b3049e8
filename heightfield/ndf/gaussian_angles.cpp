#include "heightfield/ndf/gaussian_angles.h"

#include "core/quadrature.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

double GaussianAngles::inverse_normalisation(double sigma) {
    const double s2 = 2 * sigma * sigma;
    return kTwoPi * integrate_global([s2](double t) { return std::exp(-t * t / s2) * std::sin(t); },
                                     0.0, kPi / 2, 1e-300, 1e-13); // M18 Eq. 14
}

double GaussianAngles::inverse_normalisation_series(double sigma) {
    const double s2 = sigma * sigma;
    return kTwoPi * s2 * (1 - s2 / 3 + s2 * s2 / 15 - s2 * s2 * s2 / 105);
}

namespace {
RadialProfile gaussian_profile(double sigma) {
    if (!(sigma >= GaussianAngles::kSigmaMin && sigma <= GaussianAngles::kSigmaMax))
        throw std::invalid_argument("gaussian: sigma must be in [0.001, 1.5] rad");
    RadialProfile f;
    f.name = "gaussian";
    f.parameters = parameter_list({{"sigma", sigma}});
    const double c = 1.0 / GaussianAngles::inverse_normalisation(sigma), s2 = 2 * sigma * sigma;
    f.p22 = [c, s2](double r2) { // D cos^4 = C exp(-theta^2 / 2 sigma^2) cos^3, r = tan theta
        const double theta = std::atan(std::sqrt(r2)), cos = 1.0 / std::sqrt(1.0 + r2);
        return c * std::exp(-theta * theta / s2) * cos * cos * cos;
    };
    f.bulk = std::tan(std::min(sigma, 1.2));
    f.narrow = f.wide = sigma;
    return f;
}
} // namespace

GaussianAngles::GaussianAngles(double sigma)
    : RadialNdf(1.0, 1.0, gaussian_profile(sigma)), sigma_(sigma) {}

} // namespace gonio
