#include "heightfield/ndf/beckmann.h"

#include "core/special_functions.h"
#include "heightfield/ndf/ndf_family.h"

#include <cmath>
#include <limits>

namespace gonio {

namespace {
constexpr double kSqrtPi = 1.7724538509055160273;
}

double Beckmann::d_unit(double r2, double cos2) const {
    if (r2 > 740) return 0.0; // exp underflows; also keeps 0 / 0 away at the horizon
    return std::exp(-r2) / (kPi * cos2 * cos2); // M18 Eq. 16 with alpha = 1
}

double Beckmann::lambda_unit(double t2) const {
    if (t2 <= 0) return 0.0;
    if (std::isinf(t2)) return std::numeric_limits<double>::infinity();
    const double a = 1.0 / std::sqrt(t2);
    // M18 Eq. 20, (erf(a) - 1)/2 + exp(-a^2) / (2 a sqrt(pi)), written with erfc for accuracy.
    return std::max(0.0, 0.5 * (std::exp(-a * a) / (a * kSqrtPi) - std::erfc(a)));
}

double Beckmann::sample_slope_radius2(double u) const {
    return -std::log1p(-u); // M18 Eq. 30: tan^2 theta = -log(xi) (with xi = 1 - u)
}

void Beckmann::sample_visible_slope(double c, double u1, double u2, double& x, double& y) const {
    // Heitz & d'Eon 2014 section 4: y is independent, Gaussian of variance 1/2.
    y = erf_quantile(u2);
    if (c >= 1.0) { // normal view: the visible slopes are the slopes
        x = erf_quantile(u1);
        return;
    }
    // x has density proportional to (mu - x) exp(-x^2) on x < mu, mu = cot theta. Its CDF is
    // F(x) = mu sqrt(pi)/2 erfc(-x) + exp(-x^2)/2; invert F(x) = u1 F(mu) by bracketed Newton.
    const double mu = c / std::sqrt(std::max(0.0, 1.0 - c * c));
    auto cdf = [mu](double t) { return 0.5 * (mu * kSqrtPi * std::erfc(-t) + std::exp(-t * t)); };
    const double target = u1 * cdf(mu);
    double lo = -30.0, hi = mu;
    double t = std::clamp(erf_quantile(u1), lo + 1e-3, hi - 1e-12 * (1 + std::abs(hi)));
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    for (int i = 0; i < 300; ++i) {
        const double g = cdf(t) - target;
        if (g > 0)
            hi = t;
        else
            lo = t;
        const double dg = (mu - t) * std::exp(-t * t);
        double next = dg > 0 ? t - g / dg : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - t) <= 1e-14 * (1 + std::abs(t))) {
            t = next;
            break;
        }
        t = next;
    }
    x = t;
}

} // namespace gonio

namespace gonio {
const NdfFamily& beckmann_family() {
    static const NdfFamily f{"beckmann", "Beckmann: Gaussian slopes [R19 section 2.1]",
                             roughness_keys(),
                             [](TableReader& r, int) -> std::unique_ptr<Ndf> {
                                 const Roughness a = read_roughness(r);
                                 return std::make_unique<Beckmann>(a.x, a.y);
                             },
                             true};
    return f;
}
} // namespace gonio
