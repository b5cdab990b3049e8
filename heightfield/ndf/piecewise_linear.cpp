#include "heightfield/ndf/piecewise_linear.h"

#include "core/number_text.h"
#include "heightfield/ndf/ndf_family.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {
void validate(const ControlPoints& p) {
    if (p.theta.size() != p.value.size())
        throw std::invalid_argument("piecewise_linear: as many values as control angles needed");
    if (p.theta.size() < 2)
        throw std::invalid_argument("piecewise_linear: at least 2 control points needed");
    if (p.theta.front() != 0.0 || std::abs(p.theta.back() - kPi / 2) > 1e-12)
        throw std::invalid_argument("piecewise_linear: control angles must run from 0 to 90 deg");
    for (size_t i = 1; i < p.theta.size(); ++i)
        if (!(p.theta[i] > p.theta[i - 1]))
            throw std::invalid_argument("piecewise_linear: control angles must increase");
    for (double v : p.value)
        if (!(v >= 0) || !std::isfinite(v))
            throw std::invalid_argument("piecewise_linear: values must be finite and >= 0");
}

// D_iso(theta) of normalised points, linear between them [R19 Eq. 11].
double evaluate(const ControlPoints& p, double theta) {
    const auto it = std::upper_bound(p.theta.begin(), p.theta.end(), theta);
    if (it == p.theta.begin()) return p.value.front();
    if (it == p.theta.end()) return p.value.back();
    const size_t i = size_t(it - p.theta.begin());
    const double t = (theta - p.theta[i - 1]) / (p.theta[i] - p.theta[i - 1]);
    return p.value[i - 1] + t * (p.value[i] - p.value[i - 1]);
}

RadialProfile profile(ControlPoints& p, std::string name, std::string parameters) {
    validate(p);
    if (parameters.empty()) { // user-given points: all of them, so that describe() is unique
        std::ostringstream s;
        s << "theta_deg=[";
        for (size_t i = 0; i < p.theta.size(); ++i)
            s << (i ? ", " : "") << shortest(p.theta[i] * 180 / kPi);
        s << "], value=[";
        for (size_t i = 0; i < p.value.size(); ++i) s << (i ? ", " : "") << shortest(p.value[i]);
        s << "]";
        parameters = s.str();
    }
    const double c = piecewise_linear_normalisation(p);
    if (!(c > 0)) throw std::invalid_argument("piecewise_linear: the curve is zero everywhere");
    for (double& v : p.value) v /= c;
    RadialProfile f;
    f.name = std::move(name);
    f.parameters = std::move(parameters);
    f.p22 = [p](double r2) { // P22 = D cos^4 theta, r = tan theta
        const double cos2 = 1.0 / (1.0 + r2);
        return evaluate(p, std::atan(std::sqrt(r2))) * cos2 * cos2;
    };
    double smallest = kPi / 2;
    for (size_t i = 1; i + 1 < p.theta.size(); ++i) {
        f.kinks.push_back(std::tan(p.theta[i]));
        smallest = std::min(smallest, p.theta[i] - p.theta[i - 1]);
    }
    smallest = std::min(smallest, p.theta.back() - p.theta[p.theta.size() - 2]);
    // Bulk: the median polar angle of D cos (bisection on the closed-form cumulative mass).
    double lo = 0, hi = kPi / 2;
    for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        ControlPoints head;
        for (size_t i = 0; i < p.theta.size() && p.theta[i] < mid; ++i)
            head.theta.push_back(p.theta[i]), head.value.push_back(p.value[i]);
        head.theta.push_back(mid), head.value.push_back(evaluate(p, mid));
        (piecewise_linear_normalisation(head) < 0.5 ? lo : hi) = mid;
    }
    f.bulk = std::tan(std::clamp(0.5 * (lo + hi), 1e-3, 1.4));
    f.narrow = std::max(1e-3, smallest);
    f.wide = std::atan(f.bulk);
    return f;
}
} // namespace

double piecewise_linear_normalisation(const ControlPoints& p) {
    // int (a t + b) sin t cos t dt = -(a t + b) cos(2t) / 4 + a sin(2t) / 8   [R19 Eq. 12]
    double c = 0;
    for (size_t i = 1; i < p.theta.size(); ++i) {
        const double t0 = p.theta[i - 1], t1 = p.theta[i];
        const double a = (p.value[i] - p.value[i - 1]) / (t1 - t0), b = p.value[i - 1] - a * t0;
        auto F = [&](double t) {
            return -(a * t + b) * std::cos(2 * t) / 4 + a * std::sin(2 * t) / 8;
        };
        c += F(t1) - F(t0);
    }
    return kTwoPi * c;
}

PiecewiseLinearNdf::PiecewiseLinearNdf(ControlPoints points, std::string name,
                                       std::string parameters)
    : RadialNdf(1.0, 1.0, profile(points, std::move(name), std::move(parameters))),
      points_(std::move(points)) {}

ControlPoints PiecewiseLinearNdf::sampled_from(const Ndf& source, int intervals) {
    if (intervals < 1) throw std::invalid_argument("piecewise_linear: points must be >= 2");
    ControlPoints p;
    for (int i = 0; i <= intervals; ++i) {
        const double theta = i == intervals ? kPi / 2 : 0.5 * kPi * i / intervals;
        p.theta.push_back(theta);
        // At the horizon, the limit from just above it (m.z = 0 itself is below the domain).
        p.value.push_back(source.D(spherical_direction(std::min(theta, kPi / 2 - 1e-9), 0.0)));
    }
    return p;
}

} // namespace gonio

namespace gonio {
namespace {
const Key kTheta =
    Key::numbers("theta", {0, 90}, "control points' angles, from 0 to 90, increasing")
        .in_unit("degrees")
        .cited("R19 Eq. 11");
const Key kValue = Key::numbers("value", {0, 1e300},
                                "D_iso at the control points (any scale: normalised by Eq. 12)")
                       .cited("R19 Eq. 11-12");
const Key kSource = Key::table("source", "instead of theta/value: a distribution to sample along "
                                         "φ = 0");
const Key kPoints =
    Key::integer("points", {3, 4097}, "with `source`: control points uniform in θ").fallback(65.0);
} // namespace
const NdfFamily& piecewise_linear_family() {
    static const NdfFamily f{
        "piecewise_linear",
        "piecewise-linear isotropic curve [R19 Eq. 11-12]",
        {kTheta, kValue, kSource, kPoints},
        [](TableReader& r, int depth) -> std::unique_ptr<Ndf> {
            if (r.has("source")) {
                const auto source = read_ndf(r.table(kSource), depth + 1);
                const int intervals = int(r.integer(kPoints)) - 1;
                return std::make_unique<PiecewiseLinearNdf>(
                    PiecewiseLinearNdf::sampled_from(*source, intervals), "piecewise_linear",
                    "points=" + std::to_string(intervals + 1) + " from " + source->describe());
            }
            if (!r.has("theta"))
                r.fail("theta", "missing: give theta (degrees, 0 to 90) and value, or a source "
                                "distribution to sample");
            ControlPoints points;
            for (double t : r.number_list(kTheta)) points.theta.push_back(radians(t));
            points.value = r.number_list(kValue);
            try {
                return std::make_unique<PiecewiseLinearNdf>(std::move(points));
            } catch (const std::invalid_argument& e) {
                r.fail("theta", e.what());
            }
        },
        true};
    return f;
}
} // namespace gonio
