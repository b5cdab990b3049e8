#include "sensor/beckers_sensor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gonio {

BeckersSensor::BeckersSensor(int cells) : n_(cells) {
    if (cells < 1)
        throw std::invalid_argument("BeckersSensor: cell count must be >= 1, got " +
                                    std::to_string(cells));
    // Caps from the rim inwards: S_0 = N, S_1, ..., S_last = 1 (the polar cell).
    std::vector<int> caps{n_};
    const double step = std::sqrt(kTwoPi / n_);
    double theta = kPi / 2;
    while (caps.back() > 1) {
        const int outer = caps.back();
        const double inner_theta = theta - step;
        // S_l = round(S_{l-1} sin^2(theta_l/2) / sin^2(theta_{l-1}/2)) = round(N (1 - cos
        // theta_l)).
        int s =
            inner_theta > 0 ? static_cast<int>(std::lround(n_ * (1 - std::cos(inner_theta)))) : 0;
        if (s < 7) s = 1;              // a small cap becomes one polar cell
        if (s >= outer) s = outer - 1; // always progress (only matters for tiny N)
        s = std::max(s, 1);
        caps.push_back(s);
        theta = std::acos(1.0 - static_cast<double>(s) / n_);
    }
    // Store pole first: ring_first_ = 0, 1, S_{last-1}, ..., N.
    ring_first_.push_back(0);
    for (auto it = caps.rbegin(); it != caps.rend(); ++it) ring_first_.push_back(*it);
    ring_cos_.resize(ring_first_.size());
    for (size_t r = 0; r < ring_first_.size(); ++r)
        ring_cos_[r] = 1.0 - static_cast<double>(ring_first_[r]) / n_;
    ring_cos_.back() = 0.0; // exactly the horizon

    cells_.reserve(n_);
    for (int r = 0; r < ring_count(); ++r) {
        const int count = ring_cell_count(r);
        const double z_hi = ring_cos_[r], z_lo = ring_cos_[r + 1];
        const double dphi = kTwoPi / count;
        // Equal-area midpoint in cos(theta); the polar cell's centre is the pole.
        const double z_mid = count == 1 && r == 0 ? 1.0 : 0.5 * (z_hi + z_lo);
        for (int j = 0; j < count; ++j) {
            SensorCell c;
            c.ring = r;
            c.theta_min = std::acos(z_hi);
            c.theta_max = std::acos(z_lo);
            c.phi_min = j * dphi;
            c.phi_max = j + 1 == count ? kTwoPi : (j + 1) * dphi;
            c.theta_center = std::acos(z_mid);
            c.phi_center = count == 1 ? 0.0 : (j + 0.5) * dphi;
            c.center = spherical_direction(c.theta_center, c.phi_center);
            c.solid_angle = (z_hi - z_lo) * dphi;
            c.projected_solid_angle = 0.5 * (z_hi * z_hi - z_lo * z_lo) * dphi;
            cells_.push_back(c);
        }
    }
    // Lookup tables: the ring of each bucket of u (one per unit up to 2^16 buckets), and each
    // cell's first boundary.
    const int buckets = std::min(n_, 1 << 16);
    bucket_scale_ = double(buckets) / n_;
    for (int b = 0, ring = 0; b < buckets; ++b) {
        const double u = b / bucket_scale_;
        while (ring + 1 < ring_count() && u >= ring_first_[ring + 1]) ++ring;
        ring_of_bucket_.push_back(ring);
    }
    for (int r = 0; r < ring_count(); ++r) ring_scale_.push_back(ring_cell_count(r) / kTwoPi);
    for (const SensorCell& c : cells_) {
        boundary_.push_back(std::cos(c.phi_min));
        boundary_.push_back(std::sin(c.phi_min));
    }
}

namespace {
// atan2(y, x) in [0, 2 pi) to 1.7e-6 rad (an odd minimax polynomial of atan on [0, 1]); the
// lookup decides exactly wherever that could matter.
double approximate_phi(double x, double y) {
    const double ax = std::abs(x), ay = std::abs(y);
    const double hi = std::max(ax, ay), lo = std::min(ax, ay);
    if (hi == 0) return 0;
    const double a = lo / hi, s = a * a;
    double r = a * (0.99997726 +
                    s * (-0.33262347 +
                         s * (0.19354346 + s * (-0.11643287 + s * (0.05265332 - s * 0.01172120)))));
    // Octant unfolding as selects rather than branches: the signs are random in a tracer.
    r = ay > ax ? 0.5 * kPi - r : r;
    r = x < 0 ? kPi - r : r;
    return y < 0 ? kTwoPi - r : r;
}
} // namespace

int BeckersSensor::lookup(const Vec3& d) const {
    // u = N (1 - cos theta) is the number of cells inside the cap through d; ring r holds u in
    // [ring_first_[r], ring_first_[r+1]). The bucket gives a ring at most a few steps away.
    const double u = n_ * (1.0 - std::clamp(d.z, 0.0, 1.0));
    const int buckets = static_cast<int>(ring_of_bucket_.size());
    int ring = ring_of_bucket_[std::min(static_cast<int>(u * bucket_scale_), buckets - 1)];
    // Ring boundaries are integers of u: with one bucket per unit of u (N <= 2^16) the bucket's
    // ring is exact and these loops never run.
    while (ring > 0 && u < ring_first_[ring]) --ring;
    while (ring + 1 < ring_count() && u >= ring_first_[ring + 1]) ++ring;
    const int first = ring_first_[ring], count = ring_cell_count(ring);
    if (count == 1) return first;
    if (count < 3) return first + std::min(int(spherical_phi(d) * (count / kTwoPi)), count - 1);
    // The azimuth in cell widths. The estimate is within 1.7e-6 rad of atan2 (measured on 2e7
    // directions): farther than kMargin from both boundaries, its cell is exact.
    constexpr double kMargin = 1e-4; // rad
    const double t = approximate_phi(d.x, d.y) * ring_scale_[ring];
    int j = std::clamp(static_cast<int>(t), 0, count - 1);
    const double frac = t - j, margin = kMargin * ring_scale_[ring];
    if (frac > margin && frac < 1 - margin) return first + j;
    // Near a boundary, decide exactly: d lies at or after the boundary of cell j
    // (counter-clockwise, within half a turn) and before that of cell j + 1; phi = 2 pi wraps to
    // 0. The estimate is off by at most one cell, so each loop runs at most once.
    auto after = [&](int cell) {
        return boundary_[2 * cell] * d.y - boundary_[2 * cell + 1] * d.x >= 0;
    };
    for (int guard = 0; guard < count && !after(first + j); ++guard) j = j == 0 ? count - 1 : j - 1;
    for (int guard = 0; guard < count && j + 1 < count && after(first + j + 1); ++guard) ++j;
    return first + j;
}

double BeckersSensor::ring_aspect_ratio(int ring) const {
    const SensorCell& c = cells_[ring_first_[ring]];
    const double polar = c.theta_max - c.theta_min;
    const double azimuthal = std::sin(0.5 * (c.theta_min + c.theta_max)) * (c.phi_max - c.phi_min);
    return polar / azimuthal;
}

} // namespace gonio
