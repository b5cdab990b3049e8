#include "gonio/table/sensor_lobe.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

double sample_linear(double u, double a, double b) {
    if (a == b || a + b <= 0) return u;
    // Inverse of F(x) = (a x + (b - a) x^2 / 2) / ((a + b) / 2), in the form without
    // cancellation.
    const double denominator = a + std::sqrt(a * a * (1 - u) + b * b * u);
    if (denominator <= 0) return 0; // u = 0 on a density that starts at 0
    const double x = u * (a + b) / denominator;
    return std::min(x, 0x1.fffffffffffffp-1);
}

SensorLobeGrid::SensorLobeGrid(const BeckersSensor& sensor)
    : cells_(sensor.cell_count()), sensor_(&sensor) {
    for (int r = 0; r <= sensor.ring_count(); ++r)
        first_.push_back(r < sensor.ring_count() ? sensor.ring_first_cell(r) : cells_);
    for (int r = 0; r < sensor.ring_count(); ++r) {
        const double z = std::cos(sensor.cell(first_[r]).theta_center);
        s_.push_back(r == 0 && ring_count(0) == 1 ? 0.0 : std::max(0.0, 1 - z * z));
    }
}

namespace {
// The two cells of ring [first, first + n) around azimuth phi and their weights.
void ring_weights(int first, int n, double phi, SensorLobeGrid::Weights& w, double scale) {
    if (scale <= 0) return;
    if (n == 1) {
        w.cell[w.count] = first;
        w.weight[w.count++] = scale;
        return;
    }
    const double t = phi * (n / kTwoPi) - 0.5; // in cell widths from the first centre
    const double fl = std::floor(t);
    const double frac = t - fl;
    int j0 = static_cast<int>(fl) % n;
    if (j0 < 0) j0 += n;
    const int j1 = j0 + 1 == n ? 0 : j0 + 1;
    w.cell[w.count] = first + j0;
    w.weight[w.count++] = scale * (1 - frac);
    w.cell[w.count] = first + j1;
    w.weight[w.count++] = scale * frac;
}
} // namespace

SensorLobeGrid::Weights SensorLobeGrid::weights(const Vec3& d) const {
    Weights w;
    const double l2 = dot(d, d);
    const double s = d.z <= 0 ? 1.0 : std::min(1.0, (d.x * d.x + d.y * d.y) / l2);
    const double phi = spherical_phi(d);
    const int last = rings() - 1;
    const int k = static_cast<int>(std::upper_bound(s_.begin(), s_.end(), s) - s_.begin()) - 1;
    if (k >= last) {
        ring_weights(first_[last], ring_count(last), phi, w, 1.0);
        return w;
    }
    const double t = (s - s_[k]) / (s_[k + 1] - s_[k]);
    ring_weights(first_[k], ring_count(k), phi, w, 1 - t);
    ring_weights(first_[k + 1], ring_count(k + 1), phi, w, t);
    return w;
}

double SensorLobeGrid::integral(const double* v, int stride) const {
    const int n_rings = rings();
    double total = 0, previous = 0;
    for (int r = 0; r < n_rings; ++r) {
        double sum = 0;
        for (int c = first_[r]; c < first_[r + 1]; ++c) sum += v[size_t(c) * stride];
        const double mass = sum * kTwoPi / ring_count(r); // integral over phi of the ring's curve
        if (r > 0) total += 0.25 * (s_[r] - s_[r - 1]) * (previous + mass);
        previous = mass;
    }
    return total + 0.5 * (1 - s_[n_rings - 1]) * previous;
}

SensorLobeSampler::SensorLobeSampler(const SensorLobeGrid& grid, std::vector<double> values)
    : grid_(&grid), v_(std::move(values)) {
    if (static_cast<int>(v_.size()) != grid.cells())
        throw std::invalid_argument("SensorLobeSampler: one value per cell expected");
    for (double& x : v_) x = std::max(x, 0.0);
    const int n_rings = grid.rings();
    segment_cdf_.assign(v_.size(), 0.0);
    for (int r = 0; r < n_rings; ++r) {
        const int first = grid.ring_first(r), n = grid.ring_count(r);
        double cumulative = 0;
        for (int j = 0; j < n; ++j) {
            const double next = v_[first + (j + 1 == n ? 0 : j + 1)];
            cumulative += 0.5 * (v_[first + j] + next) * (kTwoPi / n);
            segment_cdf_[first + j] = cumulative;
        }
        // A single cell's curve is constant: its mass is v 2 pi (the loop gave exactly that).
        ring_mass_.push_back(cumulative);
    }
    double cumulative = 0;
    for (int k = 0; k + 1 < n_rings; ++k) {
        cumulative +=
            0.25 * (grid.ring_s(k + 1) - grid.ring_s(k)) * (ring_mass_[k] + ring_mass_[k + 1]);
        band_cdf_.push_back(cumulative);
    }
    cumulative += 0.5 * (1 - grid.ring_s(n_rings - 1)) * ring_mass_.back();
    band_cdf_.push_back(cumulative);
    total_ = cumulative;
}

double SensorLobeSampler::eval(const Vec3& d) const {
    const SensorLobeGrid::Weights w = grid_->weights(d);
    double f = 0;
    for (int k = 0; k < w.count; ++k) f += w.weight[k] * v_[w.cell[k]];
    return f;
}

namespace {
// Index of the first entry of cdf[lo, hi) above x, and x rescaled to [0, 1) within it.
int pick(const std::vector<double>& cdf, int lo, int hi, double base, double& x) {
    const auto it = std::upper_bound(cdf.begin() + lo, cdf.begin() + hi, x);
    int k = std::min(static_cast<int>(it - cdf.begin()), hi - 1);
    // Skip entries of zero mass that x landed on at their (shared) boundary.
    while (k > lo && cdf[k] == cdf[k - 1]) --k;
    const double before = k > lo ? cdf[k - 1] : base;
    const double mass = cdf[k] - before;
    x = mass > 0 ? std::clamp((x - before) / mass, 0.0, 0x1.fffffffffffffp-1) : 0.0;
    return k;
}
} // namespace

Vec3 SensorLobeSampler::sample(double u0, double u1, double u2) const {
    const int n_rings = grid_->rings();
    double x = u1 * total_;
    const int band = pick(band_cdf_, 0, n_rings, 0.0, x);
    int ring;
    double s;
    if (band + 1 < n_rings) {
        const double a = ring_mass_[band], b = ring_mass_[band + 1];
        const double t = sample_linear(x, a, b);
        s = grid_->ring_s(band) + t * (grid_->ring_s(band + 1) - grid_->ring_s(band));
        const double pa = (1 - t) * a, pb = t * b;
        ring = u0 * (pa + pb) < pa ? band : band + 1;
    } else {
        ring = band;
        s = grid_->ring_s(band) + x * (1 - grid_->ring_s(band));
    }
    const int first = grid_->ring_first(ring), n = grid_->ring_count(ring);
    double phi;
    if (n == 1) {
        phi = kTwoPi * u2;
    } else {
        double y = u2 * ring_mass_[ring];
        const int j = pick(segment_cdf_, first, first + n, 0.0, y) - first;
        const double a = v_[first + j], b = v_[first + (j + 1 == n ? 0 : j + 1)];
        phi = (j + 0.5 + sample_linear(y, a, b)) * (kTwoPi / n);
        if (phi >= kTwoPi) phi -= kTwoPi;
    }
    s = std::clamp(s, 0.0, 1.0);
    const double r = std::sqrt(s);
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(1 - s)};
}

} // namespace gonio
