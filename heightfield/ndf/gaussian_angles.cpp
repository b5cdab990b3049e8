#include "heightfield/ndf/gaussian_angles.h"

#include "core/check.h"
#include "core/quadrature.h"
#include "heightfield/ndf/ndf_family.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

double GaussianAngles::inverse_normalisation(double sigma, double theta_max) {
    const double s2 = 2 * sigma * sigma;
    return kTwoPi * integrate_global([s2](double t) { return std::exp(-t * t / s2) * std::sin(t); },
                                     0.0, theta_max, 1e-300, 1e-13); // M18 Eq. 14
}

double GaussianAngles::inverse_normalisation_series(double sigma) {
    const double s2 = sigma * sigma;
    return kTwoPi * s2 * (1 - s2 / 3 + s2 * s2 / 15 - s2 * s2 * s2 / 105);
}

namespace {
RadialProfile gaussian_profile(double sigma, double theta_max) {
    // The keys' ranges (below), checked where they are read.
    using G = GaussianAngles;
    GONIO_DCHECK(sigma >= radians(G::kSigmaMinDeg) && sigma <= radians(G::kSigmaMaxDeg));
    GONIO_DCHECK(theta_max >= radians(G::kThetaMaxMinDeg) &&
                 theta_max <= radians(G::kThetaMaxMaxDeg));
    RadialProfile f;
    f.name = "gaussian";
    f.parameters = parameter_list({{"sigma", sigma}, {"theta_max", theta_max}});
    const double c = 1.0 / GaussianAngles::inverse_normalisation(sigma, theta_max),
                 s2 = 2 * sigma * sigma, r2_max = std::tan(theta_max) * std::tan(theta_max);
    f.p22 = [c, s2, r2_max](double r2) { // D cos^4 = C exp(-theta^2 / 2 sigma^2) cos^3
        if (r2 > r2_max) return 0.0;
        const double theta = std::atan(std::sqrt(r2)), cos = 1.0 / std::sqrt(1.0 + r2);
        return c * std::exp(-theta * theta / s2) * cos * cos * cos;
    };
    f.kinks = {std::tan(theta_max)};
    f.bulk = std::tan(std::min(sigma, 1.2));
    f.narrow = f.wide = sigma;
    return f;
}
} // namespace

GaussianAngles::GaussianAngles(double sigma, double theta_max)
    : RadialNdf(1.0, 1.0, gaussian_profile(sigma, theta_max)), sigma_(sigma),
      theta_max_(theta_max) {}

} // namespace gonio

namespace gonio {
namespace {
// Degrees in the config, like every angle; the range is the constructor's in radians.
const Key kSigma =
    Key::number("sigma", {GaussianAngles::kSigmaMinDeg, GaussianAngles::kSigmaMaxDeg},
                "σ of the Gaussian of angles")
        .in_unit("degrees")
        .cited("M18 Eq. 14");
const Key kThetaMax =
    Key::number("theta_max", {GaussianAngles::kThetaMaxMinDeg, GaussianAngles::kThetaMaxMaxDeg},
                "where the Gaussian is cut (uncut, its 1/cos θ makes Smith's Λ infinite)")
        .in_unit("degrees")
        .fallback(89.9);
} // namespace
const NdfFamily& gaussian_family() {
    static const NdfFamily f{"gaussian",
                             "Gaussian of angles [M18 Eq. 14]",
                             {kSigma, kThetaMax},
                             [](TableReader& r, int) -> std::unique_ptr<Ndf> {
                                 const double sigma = radians(r.number(kSigma));
                                 return std::make_unique<GaussianAngles>(
                                     sigma, radians(r.number(kThetaMax)));
                             },
                             true};
    return f;
}
} // namespace gonio
