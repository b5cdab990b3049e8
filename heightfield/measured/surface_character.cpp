#include "heightfield/measured/surface_character.h"

#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/surface_metrics.h"

#include <cmath>
#include <cstdio>
#include <functional>

namespace gonio {

namespace {
constexpr double kLowest = 1e-3, kHighest = 20; // the roughness searched

// Golden-section search of the x in [a, b] minimising f, to `tolerance` (f is unimodal here).
double golden_minimum(const std::function<double(double)>& f, double a, double b,
                      double tolerance) {
    const double g = (std::sqrt(5.0) - 1) / 2;
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = f(c), fd = f(d);
    for (int k = 0; k < 60 && b - a > tolerance; ++k) {
        if (fc < fd)
            b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
        else
            a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
    }
    return 0.5 * (a + b);
}

// The isotropic alpha minimising the TV distance, by golden-section search of log alpha over
// [1e-3, 20] (a bracket taken from the RMS slope would miss heavy-tailed maps, whose RMS slope
// far exceeds their typical one). Then alpha_x and alpha_y from it, by alternating searches of
// one with the other held, over a factor of 4 either side, until neither moves by 0.1 %.
template <class Family>
void fit(const std::vector<double>& facets, int bins, const char* name, AnalyticFit& iso,
         AnalyticFit& xy) {
    auto distance = [&](double ax, double ay) {
        return total_variation(facets, target_cell_mass(Family(ax, ay), bins));
    };
    const double log_alpha =
        golden_minimum([&](double l) { return distance(std::exp(l), std::exp(l)); },
                       std::log(kLowest), std::log(kHighest), 1e-4);
    iso.family = xy.family = name;
    iso.alpha_x = iso.alpha_y = std::exp(log_alpha);
    iso.distance = distance(iso.alpha_x, iso.alpha_y);

    double lx = log_alpha, ly = log_alpha;
    const double reach = std::log(4.0), lo = std::log(kLowest), hi = std::log(kHighest);
    for (int round = 0; round < 8; ++round) {
        const double x =
            golden_minimum([&](double l) { return distance(std::exp(l), std::exp(ly)); },
                           std::max(lo, lx - reach), std::min(hi, lx + reach), 1e-4);
        const double y =
            golden_minimum([&](double l) { return distance(std::exp(x), std::exp(l)); },
                           std::max(lo, ly - reach), std::min(hi, ly + reach), 1e-4);
        const bool settled = std::abs(x - lx) < 1e-3 && std::abs(y - ly) < 1e-3;
        lx = x, ly = y;
        if (settled) break;
    }
    xy.alpha_x = std::exp(lx), xy.alpha_y = std::exp(ly);
    xy.distance = distance(xy.alpha_x, xy.alpha_y);
    if (xy.distance > iso.distance) xy = iso; // never worse than the isotropic fit
}
} // namespace

std::string AnalyticFit::ndf_toml() const {
    char text[160];
    if (isotropic())
        std::snprintf(text, sizeof text, "{ type = \"%s\", alpha = %.4g }", family.c_str(),
                      alpha_x);
    else
        std::snprintf(text, sizeof text, "{ type = \"%s\", alpha_x = %.4g, alpha_y = %.4g }",
                      family.c_str(), alpha_x, alpha_y);
    return text;
}

std::string SurfaceCharacter::summary() const {
    char text[480];
    std::snprintf(text, sizeof text,
                  "principal slopes: sqrt(2) RMS %.4f along %.1f deg, %.4f across; "
                  "correlation length x %.4g y %.4g; closest "
                  "analytic (TV distance): ggx alpha %.4f (%.4f), beckmann alpha %.4f (%.4f); "
                  "along x and y: ggx %.4f %.4f (%.4f), beckmann %.4f %.4f (%.4f)",
                  alpha_major, major_axis_deg, alpha_minor, correlation_x, correlation_y,
                  ggx.alpha_x, ggx.distance, beckmann.alpha_x, beckmann.distance, ggx_xy.alpha_x,
                  ggx_xy.alpha_y, ggx_xy.distance, beckmann_xy.alpha_x, beckmann_xy.alpha_y,
                  beckmann_xy.distance);
    return text;
}

SurfaceCharacter characterise_surface(const HeightField& s, int bins) {
    // The slopes' covariance over every triangle (both of a cell have the same area).
    double sxx = 0, syy = 0, sxy = 0, mx = 0, my = 0;
    const double count = 2.0 * s.n * s.n;
    for (int y = 0; y < s.n; ++y)
        for (int x = 0; x < s.n; ++x)
            for (int t = 0; t < 2; ++t) {
                double p, q;
                s.triangle_slopes(x, y, t, p, q);
                mx += p, my += q, sxx += p * p, syy += q * q, sxy += p * q;
            }
    mx /= count, my /= count;
    sxx = sxx / count - mx * mx, syy = syy / count - my * my, sxy = sxy / count - mx * my;
    // The eigenvalues and the first eigenvector's azimuth of [[sxx, sxy], [sxy, syy]].
    const double mean = 0.5 * (sxx + syy), half = std::hypot(0.5 * (sxx - syy), sxy);
    SurfaceCharacter c;
    c.alpha_major = std::sqrt(2 * std::max(mean + half, 0.0));
    c.alpha_minor = std::sqrt(2 * std::max(mean - half, 0.0));
    double axis = 0.5 * std::atan2(2 * sxy, sxx - syy) * 180 / M_PI;
    if (axis < 0) axis += 180;
    c.major_axis_deg = axis >= 180 ? axis - 180 : axis;
    correlation_lengths(s, c.correlation_x, c.correlation_y);
    const std::vector<double> facets = facet_cell_mass(s, bins);
    fit<Ggx>(facets, bins, "ggx", c.ggx, c.ggx_xy);
    fit<Beckmann>(facets, bins, "beckmann", c.beckmann, c.beckmann_xy);
    return c;
}

} // namespace gonio
