#include "heightfield/ndf/radial_table.h"

#include "core/quadrature.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

RadialTable::RadialTable(std::function<double(double)> f, int k, double scale,
                         const std::vector<double>& kinks, int nodes)
    : f_(std::move(f)), k_(k), scale_(scale) {
    if (!(scale > 0) || nodes < 8) throw std::invalid_argument("RadialTable: bad scale or nodes");
    for (int j = 0; j < nodes; ++j) w_.push_back(double(j) / nodes);
    for (double r : kinks)
        if (r > 0 && std::isfinite(r)) w_.push_back(r / (scale_ + r));
    std::sort(w_.begin(), w_.end());
    w_.erase(std::unique(w_.begin(), w_.end()), w_.end());
    w_.push_back(1.0); // r = infinity: the last interval holds the tail
    cdf_.assign(w_.size(), 0.0);
    pdf_start_.assign(w_.size(), 0.0);
    pdf_end_.assign(w_.size(), 0.0);
    for (size_t j = 0; j + 1 < w_.size(); ++j) {
        // One-sided limits: at a kink the density may jump (a distribution cut at a slope).
        const double inside = 1e-9 * (w_[j + 1] - w_[j]);
        pdf_start_[j] = density_w(w_[j] + inside);
        pdf_end_[j] = density_w(w_[j + 1] - inside);
        cdf_[j + 1] = cdf_[j] + integrate_global([this](double w) { return density_w(w); }, w_[j],
                                                 w_[j + 1], 1e-300, 1e-12, 400);
    }
    total_ = cdf_.back();
    if (!(total_ > 0) || !std::isfinite(total_))
        throw std::invalid_argument("RadialTable: the radial density has no finite, positive mass");
}

double RadialTable::density_w(double w) const {
    if (w >= 1.0) return 0.0;
    const double r = radius(w), drdw = scale_ / ((1.0 - w) * (1.0 - w));
    return std::pow(r, k_) * f_(r) * drdw;
}

double RadialTable::sample(double u) const {
    const double target = std::clamp(u, 0.0, 1.0) * total_;
    const size_t j =
        std::min<size_t>(size_t(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin()),
                         cdf_.size() - 1) -
        1;
    const double w0 = w_[j], w1 = w_[j + 1], c0 = cdf_[j], c1 = cdf_[j + 1];
    if (!(c1 > c0)) return radius(w0);
    if (j + 2 == w_.size()) {
        // The tail interval (up to r = infinity): bisection on exact integrals. Its mass is
        // tiny, so this is rare.
        double lo = w0, hi = w1;
        for (int it = 0; it < 60; ++it) {
            const double mid = 0.5 * (lo + hi);
            const double c = c0 + integrate_global([this](double w) { return density_w(w); }, w0,
                                                   mid, 1e-300, 1e-10, 200);
            (c < target ? lo : hi) = mid;
        }
        return radius(0.5 * (lo + hi));
    }
    // Cubic Hermite CDF on the interval, in t in [0, 1]: solve H(t) = target by safeguarded
    // Newton, starting from the linear guess.
    const double h = w1 - w0, d0 = pdf_start_[j] * h, d1 = pdf_end_[j] * h;
    auto H = [&](double t, double& dH) {
        const double t2 = t * t, t3 = t2 * t;
        dH = (6 * t - 6 * t2) * c0 + (3 * t2 - 4 * t + 1) * d0 + (6 * t2 - 6 * t) * c1 +
             (3 * t2 - 2 * t) * d1;
        return (2 * t3 - 3 * t2 + 1) * c0 + (t3 - 2 * t2 + t) * d0 + (-2 * t3 + 3 * t2) * c1 +
               (t3 - t2) * d1;
    };
    double lo = 0, hi = 1, t = (target - c0) / (c1 - c0);
    for (int it = 0; it < 50; ++it) {
        double dH;
        const double e = H(t, dH) - target;
        (e < 0 ? lo : hi) = t;
        if (std::abs(e) <= 1e-15 * total_) break;
        double next = dH > 0 ? t - e / dH : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - t) < 1e-15) {
            t = next;
            break;
        }
        t = next;
    }
    return radius(w0 + t * h);
}

} // namespace gonio
