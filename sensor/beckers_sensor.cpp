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
}

int BeckersSensor::lookup(const Vec3& d) const {
    // u = N (1 - cos theta) is the number of cells inside the cap through d.
    const double u = n_ * (1.0 - std::clamp(d.z, 0.0, 1.0));
    // Ring r holds u in [ring_first_[r], ring_first_[r+1]); upper_bound finds the first cap
    // boundary above u.
    auto it = std::upper_bound(ring_first_.begin() + 1, ring_first_.end(), u,
                               [](double value, int bound) { return value < bound; });
    int ring = static_cast<int>(it - ring_first_.begin()) - 1;
    ring = std::min(ring, ring_count() - 1);
    const int count = ring_cell_count(ring);
    if (count == 1) return ring_first_[ring];
    const double phi = spherical_phi(d);
    int j = static_cast<int>(phi * (count / kTwoPi));
    j = std::clamp(j, 0, count - 1); // phi = 2 pi (after round-off) stays in the last cell
    return ring_first_[ring] + j;
}

double BeckersSensor::ring_aspect_ratio(int ring) const {
    const SensorCell& c = cells_[ring_first_[ring]];
    const double polar = c.theta_max - c.theta_min;
    const double azimuthal = std::sin(0.5 * (c.theta_min + c.theta_max)) * (c.phi_max - c.phi_min);
    return polar / azimuthal;
}

} // namespace gonio
