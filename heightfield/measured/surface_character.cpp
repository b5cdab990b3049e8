#include "heightfield/measured/surface_character.h"

#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/surface_metrics.h"

#include <cmath>

namespace gonio {

namespace {
// Golden-section search of the alpha minimising the TV distance, on log alpha over [1e-3, 20]
// (the distance is unimodal in alpha for these families; a bracket taken from the RMS slope
// would miss heavy-tailed maps, whose RMS slope far exceeds their typical one).
template <class Family>
AnalyticFit fit(const HeightField& s, int bins, const char* name) {
    auto distance = [&](double log_alpha) {
        return ndf_distance(s, Family(std::exp(log_alpha)), bins);
    };
    double a = std::log(1e-3), b = std::log(20.0);
    const double g = (std::sqrt(5.0) - 1) / 2;
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = distance(c), fd = distance(d);
    for (int k = 0; k < 60 && b - a > 1e-4; ++k) {
        if (fc < fd)
            b = d, d = c, fd = fc, c = b - g * (b - a), fc = distance(c);
        else
            a = c, c = d, fc = fd, d = a + g * (b - a), fd = distance(d);
    }
    AnalyticFit f;
    f.family = name;
    f.alpha = std::exp(0.5 * (a + b));
    f.distance = distance(std::log(f.alpha));
    return f;
}
} // namespace

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
    c.ggx = fit<Ggx>(s, bins, "ggx");
    c.beckmann = fit<Beckmann>(s, bins, "beckmann");
    return c;
}

} // namespace gonio
