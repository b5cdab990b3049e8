#include "heightfield/slope_marginal.h"

#include "core/check.h"
#include "core/math.h"
#include "core/parallel.h"
#include "core/quadrature.h"

#include <algorithm>
#include <cmath>

namespace gonio {

TargetQuantiles::TargetQuantiles(const Ndf& ndf, std::size_t samples)
    : edge_(0.5 / double(samples)) {
    double ax = 1, ay = 1;
    const bool stretched = ndf.slope_stretch(ax, ay);
    GONIO_CHECK(stretched);
    // The unit-roughness squared slope radius at radial rank u = 1 - exp(-s), tabulated at
    // 2^14 + 1 steps of s up to 30 (u within 1e-13 of 1): samplers that invert numerically
    // (Student's t) cost microseconds a call, and the integrals below take ~10^6 of them.
    std::vector<double> r2(kRadii + 1);
    parallel_for(0, kRadii + 1, [&](int k) {
        const double u = -std::expm1(-kMaxS * k / kRadii);
        const Vec3 m = ndf.sample_m(u, 0.0); // azimuth 0: the slope lies along x
        const double r = std::abs(m.x) / std::max(m.z, 1e-300) / ax;
        r2[size_t(k)] = r * r;
    });
    // The radius at rank u in [0, 1): r^2 linear in s (exactly so for Beckmann, where
    // r^2 = s; to ~1e-6 relative for GGX's e^s - 1).
    auto radius = [&r2](double u) {
        const double t = -std::log1p(-u) * (kRadii / kMaxS);
        const int k = std::min(int(t), kRadii - 1);
        return std::sqrt(
            std::max(0.0, r2[size_t(k)] + (t - k) * (r2[size_t(k) + 1] - r2[size_t(k)])));
    };
    const GaussLegendre& rule = gauss_legendre(32);
    auto tail_probability = [&](double u0) { // P(|X| > radius(u0))
        const double x = radius(u0);
        double sum = 0;
        for (size_t k = 0; k < rule.nodes.size(); ++k) {
            // u = u0 + (1 - u0) w(s), s in [0, 1], w the smoothstep: smooth at both ends,
            // where the integrand has square-root kinks (arccos near 1, and R -> infinity).
            const double s = 0.5 * (rule.nodes[k] + 1), w = s * s * (3 - 2 * s);
            const double dw = 6 * s * (1 - s), u = u0 + (1 - u0) * w;
            const double r = u < 1 ? radius(u) : 1e300;
            sum += 0.5 * rule.weights[k] * dw * std::acos(std::min(1.0, x / r));
        }
        return (1 - u0) * sum * (2 / kPi);
    };
    // Body: (x, P(|X| > x)) at radial ranks k / kGrid, P decreasing.
    std::vector<double> grid_x(kGrid), grid_tau(kGrid);
    parallel_for(0, kGrid, [&](int k) {
        const double u0 = double(k) / kGrid;
        grid_x[size_t(k)] = k == 0 ? 0.0 : radius(u0);
        grid_tau[size_t(k)] = k == 0 ? 1.0 : tail_probability(u0);
    });
    // Tail: x with P(|X| > x) = tau at tau = 2^-8 2^(-i/4), down to 1e-12.
    for (double tau = kTailStart; tau >= 1e-12; tau *= 0.8408964152537145 /* 2^-1/4 */) {
        double lo = 0, hi = 1; // tail_probability decreases with u0
        for (int it = 0; it < 64; ++it) {
            const double mid = 0.5 * (lo + hi);
            (tail_probability(mid) > tau ? lo : hi) = mid;
        }
        tail_log_tau_.push_back(std::log(tau));
        tail_log_x_.push_back(std::log(std::max(radius(0.5 * (lo + hi)), 1e-30)));
    }
    // The table over u in [0, 1]: |X| at rank |2u - 1|, the sign of u - 1/2.
    table_.resize(kSize + 1);
    size_t k = 0;
    for (int i = kSize / 2; i <= kSize; ++i) {
        const double tau = 1 - (2 * double(i) / kSize - 1); // P(|X| > x) at this node
        double x;
        if (tau <= kTailStart) {
            x = tail(std::max(tau, 1e-300));
        } else {
            while (k + 2 < grid_tau.size() && grid_tau[k + 1] >= tau) ++k;
            const double f = (grid_tau[k] - tau) / std::max(grid_tau[k] - grid_tau[k + 1], 1e-300);
            x = grid_x[k] + std::clamp(f, 0.0, 1.0) * (grid_x[k + 1] - grid_x[k]);
        }
        table_[size_t(i)] = float(x);
        table_[size_t(kSize - i)] = float(-x);
    }
}

float TargetQuantiles::operator()(double u) const {
    u = std::clamp(u, edge_, 1 - edge_);
    const double v = std::abs(2 * u - 1);
    if (1 - v <= kTailStart) { // the tails, where the table's steps are too coarse
        const float x = float(tail(1 - v));
        return u < 0.5 ? -x : x;
    }
    const double t = u * kSize;
    const int i = int(t);
    const float f = float(t - i);
    return table_[i] + f * (table_[i + 1] - table_[i]);
}

double TargetQuantiles::tail(double tau) const {
    const double l = std::log(tau);
    const size_t last = tail_log_tau_.size() - 1;
    if (l >= tail_log_tau_[0]) return std::exp(tail_log_x_[0]);
    if (l <= tail_log_tau_[last]) return std::exp(tail_log_x_[last]);
    // The first node below l (tail_log_tau_ decreases).
    const size_t k = size_t(std::upper_bound(tail_log_tau_.begin(), tail_log_tau_.end(), l,
                                             [](double a, double b) { return a > b; }) -
                            tail_log_tau_.begin()) -
                     1;
    const double f = (l - tail_log_tau_[k]) / (tail_log_tau_[k + 1] - tail_log_tau_[k]);
    return std::exp(tail_log_x_[k] + f * (tail_log_x_[k + 1] - tail_log_x_[k]));
}

} // namespace gonio
