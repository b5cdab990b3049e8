#include "heightfield/ndf/radial_ndf.h"

#include "core/catmull_rom.h"
#include "core/number_text.h"
#include "core/quadrature.h"
#include "core/random.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace gonio {

namespace {
constexpr int kLambdaIntervals = 1024; // polar angles of the Lambda table, minus one
} // namespace

std::string parameter_list(std::initializer_list<std::pair<const char*, double>> values) {
    std::ostringstream s;
    for (const auto& [name, value] : values)
        s << (s.tellp() > 0 ? ", " : "") << name << "=" << shortest(value);
    return s.str();
}

RadialNdf::RadialNdf(double alpha_x, double alpha_y, RadialProfile profile)
    : ShapeInvariantNdf(alpha_x, alpha_y), profile_(std::move(profile)) {
    const auto f = [p22 = profile_.p22](double r) { return p22(r * r); };
    radius_ = std::make_unique<RadialTable>(f, 1, profile_.bulk, profile_.kinks);
    radius2_ = std::make_unique<RadialTable>(f, 2, profile_.bulk, profile_.kinks);
    // Lambda: g(mu) = E[(x - mu)+] = 2 int_mu^inf P22_1(r) r (sqrt(r^2 - mu^2) - mu acos(mu/r)) dr
    // (the slope-marginal integral of R19 Eq. 7-8 in polar slope coordinates), integrated in
    // w = r / (s + r) so that heavy tails need no cut-off.
    const double s = profile_.bulk;
    g_.assign(kLambdaIntervals + 1, 0.0);
    for (int j = 1; j <= kLambdaIntervals; ++j) {
        const double theta = 0.5 * kPi * j / kLambdaIntervals;
        const double mu = j == kLambdaIntervals ? 0.0 : 1.0 / std::tan(theta);
        auto integrand = [&](double w) {
            if (w >= 1.0) return 0.0;
            const double r = s * w / (1.0 - w), drdw = s / ((1.0 - w) * (1.0 - w));
            if (r <= mu) return 0.0;
            const double shape = std::sqrt(r * r - mu * mu) - mu * std::acos(std::min(1.0, mu / r));
            return 2.0 * f(r) * r * shape * drdw;
        };
        std::vector<double> breaks{mu / (s + mu)};
        for (double k : profile_.kinks)
            if (k > mu && std::isfinite(k)) breaks.push_back(k / (s + k));
        breaks.push_back(1.0);
        std::sort(breaks.begin(), breaks.end());
        double g = 0;
        for (size_t b = 0; b + 1 < breaks.size(); ++b)
            g += integrate_global(integrand, breaks[b], breaks[b + 1], 1e-300, 1e-11, 400);
        g_[j] = g;
    }
}

std::string RadialNdf::describe() const {
    std::ostringstream s;
    s << name() << "(alpha_x=" << shortest(alpha_x()) << ", alpha_y=" << shortest(alpha_y());
    if (!profile_.parameters.empty()) s << ", " << profile_.parameters;
    s << ")";
    return s.str();
}

double RadialNdf::narrowest_feature() const {
    return std::min(alpha_x(), alpha_y()) * profile_.narrow;
}
double RadialNdf::widest_feature() const {
    return std::max(alpha_x(), alpha_y()) * profile_.wide;
}

double RadialNdf::d_unit(double r2, double cos2) const {
    return profile_.p22(r2) / (cos2 * cos2); // R19 Eq. 6
}

double RadialNdf::g_of_theta(double theta) const {
    return catmull_rom(g_, std::clamp(theta / (0.5 * kPi), 0.0, 1.0) * kLambdaIntervals);
}

double RadialNdf::lambda_unit(double t2) const {
    if (std::isinf(t2)) return std::numeric_limits<double>::infinity();
    if (t2 <= 0) return 0.0;
    const double t = std::sqrt(t2);
    return std::max(0.0, g_of_theta(std::atan(t)) * t); // Lambda = E[(x - mu)+] / mu
}

double RadialNdf::sample_slope_radius2(double u) const {
    const double r = radius_->sample(u);
    return r * r;
}

void RadialNdf::sample_visible_slope(double c, double u1, double u2, double& x, double& y) const {
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - c * c));
    Rng rng{bits_of(u1), bits_of(u2), 0x76697369626c65ull};
    if (sin_t == 0) { // seen from the normal: visible normals are distributed as D cos
        const double r = radius_->sample(u1), phi = kTwoPi * u2;
        x = r * std::cos(phi), y = r * std::sin(phi);
        return;
    }
    const double mu = c / sin_t, mean_abs_x = 4.0 * radius2_->total();
    for (bool first = true;; first = false) {
        const double a = first ? u1 : rng.uniform(), b = first ? u2 : rng.uniform();
        double r, phi;
        if (rng.uniform() * (mu + mean_abs_x) < mu) { // proposal mu P22_1
            r = radius_->sample(a), phi = kTwoPi * b;
        } else { // proposal |x| P22_1: radius from r^2 P22_1, azimuth from |cos phi|
            r = radius2_->sample(a);
            phi = std::asin(2.0 * b - 1.0) + (rng.uniform() < 0.5 ? 0.0 : kPi);
        }
        x = r * std::cos(phi), y = r * std::sin(phi);
        // Accept with (mu - x)+ / (mu + |x|) <= 1: the density becomes (mu - x)+ P22_1.
        if (rng.uniform() * (mu + std::abs(x)) < mu - x) return;
    }
}

} // namespace gonio
