#pragma once
// A continuous lobe over the Beckers sensor: the cell averages f_c of one incidence, interpolated
// between neighbouring cell centres instead of looked up piecewise constant.
//
// The interpolant lives in (s, phi) with s = sin^2 theta, where cos theta dw = ds dphi / 2: the
// knots are the ring centres (the polar cell at s = 0, ring r at s_r of its equal-area centre);
// along a ring the lobe is linear in phi between the cells' centres (periodic); between rings r
// and r + 1 it is linear in s; beyond the outermost centre it is constant up to the horizon. Such a
// lobe has an exact integral and an exact inverse-CDF sampler (linear in s, then piecewise linear
// in phi), so `sample` returns directions with pdf exactly proportional to f cos theta.
#include "core/math.h"
#include "sensor/beckers_sensor.h"

#include <array>
#include <vector>

namespace gonio {

// The sensor's interpolation geometry, shared by every lobe on it.
class SensorLobeGrid {
  public:
    explicit SensorLobeGrid(const BeckersSensor& sensor);

    struct Weights {
        std::array<int, 4> cell{};
        std::array<double, 4> weight{};
        int count = 0;
    };
    // The cells and weights of the interpolant at d (upper hemisphere; d.z is clamped to >= 0).
    Weights weights(const Vec3& d) const;
    // Integral of the interpolant of the values v (one per cell) times cos theta over the
    // hemisphere.
    double integral(const double* v, int stride = 1) const;

    int cells() const { return cells_; }
    int rings() const { return static_cast<int>(first_.size()) - 1; }
    int ring_first(int r) const { return first_[r]; }
    int ring_count(int r) const { return first_[r + 1] - first_[r]; }
    double ring_s(int r) const { return s_[r]; }

  private:
    int cells_;
    const BeckersSensor* sensor_;
    std::vector<int> first_; // ring r holds cells [first_[r], first_[r+1])
    std::vector<double> s_;  // sin^2 of the ring's centre
};

// One lobe's sampler: a non-negative scalar per cell (e.g. the mean over channels).
class SensorLobeSampler {
  public:
    SensorLobeSampler() = default;
    SensorLobeSampler(const SensorLobeGrid& grid, std::vector<double> values);

    // Integral of the interpolated lobe times cos theta (0: nothing to sample).
    double total() const { return total_; }
    double eval(const Vec3& d) const;
    // A direction of the upper hemisphere with pdf eval(d) cos theta / total(), from three
    // uniforms in [0, 1). Requires total() > 0.
    Vec3 sample(double u0, double u1, double u2) const;
    double pdf(const Vec3& d) const {
        return total_ > 0 ? eval(d) * std::max(d.z, 0.0) / total_ : 0;
    }

  private:
    const SensorLobeGrid* grid_ = nullptr;
    std::vector<double> v_;           // per cell
    std::vector<double> ring_mass_;   // per ring: integral of the ring's curve over phi
    std::vector<double> segment_cdf_; // per cell: cumulative segment masses within its ring
    std::vector<double> band_cdf_;    // per band (between ring centres; the last to the horizon)
    double total_ = 0;
};

// x in [0, 1] with density proportional to (1 - x) a + x b (a, b >= 0), from u in [0, 1).
double sample_linear(double u, double a, double b);

} // namespace gonio
