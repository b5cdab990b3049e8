#include "heightfield/measured/surface_character.h"

#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/surface_metrics.h"
#include "sensor/beckers_sensor.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <functional>
#include <utility>

namespace gonio {

namespace {
constexpr double kHighest = 20; // the largest roughness searched

// Golden-section search of the x in [a, b] minimising f, to `tolerance`; the best point it
// evaluated (f is unimodal in log alpha for these families where the cells resolve them).
double golden_minimum(const std::function<double(double)>& f, double a, double b,
                      double tolerance) {
    const double g = (std::sqrt(5.0) - 1) / 2;
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = f(c), fd = f(d);
    double best = fc <= fd ? c : d, best_f = std::min(fc, fd);
    for (int k = 0; k < 60 && b - a > tolerance; ++k) {
        if (fc < fd)
            b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
        else
            a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
        if (fc < best_f) best = c, best_f = fc;
        if (fd < best_f) best = d, best_f = fd;
    }
    return best;
}

// The isotropic alpha minimising the TV distance, by golden-section search of log alpha over
// [lowest, 20] (a bracket taken from the RMS slope would miss heavy-tailed maps, whose RMS slope
// far exceeds their typical one). Then alpha_x and alpha_y from it, by alternating searches of
// one with the other held, each over a factor of 4 either side of its last value, for at most 8
// rounds or until neither moves by 0.1 %.
template <class Family>
void fit(const std::vector<double>& facets, int bins, double lowest, const char* name,
         AnalyticFit& iso, AnalyticFit& xy) {
    auto distance = [&](double ax, double ay) {
        return total_variation(facets, target_cell_mass(Family(ax, ay), bins));
    };
    const double lo = std::log(lowest), hi = std::log(kHighest);
    const double log_alpha =
        golden_minimum([&](double l) { return distance(std::exp(l), std::exp(l)); }, lo, hi, 1e-4);
    iso.family = xy.family = name;
    iso.alpha_x = iso.alpha_y = std::exp(log_alpha);
    iso.distance = distance(iso.alpha_x, iso.alpha_y);
    // Within 0.1 % of an end of the search (golden_minimum's tolerance is 0.01 %).
    auto mark_ends = [&](AnalyticFit& f, double l1, double l2) {
        f.at_lowest = std::min(l1, l2) < lo + 1e-3;
        f.at_highest = std::max(l1, l2) > hi - 1e-3;
    };
    mark_ends(iso, log_alpha, log_alpha);

    double lx = log_alpha, ly = log_alpha;
    const double reach = std::log(4.0);
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
    mark_ends(xy, lx, ly);
    if (xy.distance > iso.distance) xy = iso; // never worse than the isotropic fit
}

std::string format(const char* pattern, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* pattern, ...) {
    char text[256];
    va_list args;
    va_start(args, pattern);
    std::vsnprintf(text, sizeof text, pattern, args);
    va_end(args);
    return text;
}

std::string length(double value, bool capped) {
    return (capped ? ">= " : "") + format("%.4g", value);
}
} // namespace

bool AnalyticFit::isotropic() const {
    return std::abs(alpha_x - alpha_y) <= 1e-3 * std::max(alpha_x, alpha_y);
}

std::string AnalyticFit::ndf_toml() const {
    if (isotropic())
        return format("{ type = \"%s\", alpha = %.4g }", family.c_str(), 0.5 * (alpha_x + alpha_y));
    return format("{ type = \"%s\", alpha_x = %.4g, alpha_y = %.4g }", family.c_str(), alpha_x,
                  alpha_y);
}

std::vector<std::string> SurfaceCharacter::lines() const {
    std::vector<std::string> out;
    // The anisotropy is their ratio, where the slopes across are not all 0.
    out.push_back(format("slopes: sqrt(2) RMS %.4f along %.1f deg, %.4f across", alpha_major,
                         major_axis_deg, alpha_minor) +
                  (alpha_minor > 0 ? format(" (anisotropy %.3g)", alpha_major / alpha_minor) : ""));
    if (unresolved) {
        out.push_back(format("closest analytic NDFs: none: 99 %% of the facets are in the metric's "
                             "central cell, smoother than it resolves (alpha < %.3g)",
                             lowest_alpha));
        return out;
    }
    out.push_back(format("closest analytic NDFs (TV distance): ggx alpha %.4f (%.4f), beckmann "
                         "alpha %.4f (%.4f)",
                         ggx.alpha_x, ggx.distance, beckmann.alpha_x, beckmann.distance));
    out.push_back(format("along x and y: ggx %.4f %.4f (%.4f), beckmann %.4f %.4f (%.4f)",
                         ggx_xy.alpha_x, ggx_xy.alpha_y, ggx_xy.distance, beckmann_xy.alpha_x,
                         beckmann_xy.alpha_y, beckmann_xy.distance));
    // One line per family whose isotropic or x/y fit ends at an end of the search.
    for (const auto& [iso, xy] : {std::pair{&ggx, &ggx_xy}, std::pair{&beckmann, &beckmann_xy}}) {
        if (iso->at_lowest || xy->at_lowest)
            out.push_back(format("%s: at the lowest alpha the metric resolves (%.4f); its closest "
                                 "may be narrower still",
                                 iso->family.c_str(), lowest_alpha));
        if (iso->at_highest || xy->at_highest)
            out.push_back(format("%s: at the highest alpha searched (%g); its closest may be "
                                 "steeper still",
                                 iso->family.c_str(), kHighest));
    }
    out.push_back("closest: ndf = " + best_xy().ndf_toml() +
                  " (isotropic: ndf = " + best().ndf_toml() + ")");
    return out;
}

std::string SurfaceCharacter::summary() const {
    std::string text = "correlation length: x " + length(correlation_x, correlation_x_capped) +
                       ", y " + length(correlation_y, correlation_y_capped);
    for (const std::string& line : lines()) text += "; " + line;
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
    const double cap = 0.5 * s.n * s.spacing; // surface_metrics' "never fell below 1/e"
    c.correlation_x_capped = c.correlation_x >= cap;
    c.correlation_y_capped = c.correlation_y >= cap;

    // The central cell of `bins` equal-area cells is the cap 1 - cos(theta) = 1 / bins, i.e.
    // tan(theta) ~ sqrt(2 / bins); its 2 x 8 Gauss-Legendre nodes in cos(theta) follow GGX and
    // Beckmann to 0.1 % down to a quarter of that (alpha 0.011 at 1000 cells; 0.003: 30 % off).
    const BeckersSensor sensor(bins);
    c.lowest_alpha = 0.25 * std::sqrt(2.0 / bins);
    const std::vector<double> facets = facet_cell_mass(s, bins);
    c.unresolved = facets[size_t(sensor.lookup({0, 0, 1}))] >= 0.99;
    fit<Ggx>(facets, bins, c.lowest_alpha, "ggx", c.ggx, c.ggx_xy);
    fit<Beckmann>(facets, bins, c.lowest_alpha, "beckmann", c.beckmann, c.beckmann_xy);
    return c;
}

} // namespace gonio
