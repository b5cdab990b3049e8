#pragma once
// Quantile functions of a slope distribution's 1-D marginal (slopes projected on a direction), what
// sliced matching (generate.cpp) matches each direction's projections to.
#include "heightfield/ndf/ndf.h"

#include <cstddef>
#include <vector>

namespace gonio {

// A quantile function of the target's 1-D marginal (of slopes projected on a direction, in the
// frame where the matching works), evaluated at the rank fractions of the histogram's bin edges.
class MarginalQuantile {
  public:
    virtual ~MarginalQuantile() = default;
    virtual float operator()(double u) const = 0;
};

// The exact marginal of a shape-invariant NDF in its stretched frame, where the slopes are
// isotropic: X = R cos(phi), R the unit-roughness slope radius (the NDF's own radial inverse CDF,
// through sample_m), phi uniform, so that P(|X| > x) = (2/pi) int_{R > x} arccos(x / R) dF_R.
// No pool and no sort of n^2 values: that integral is taken by Gauss-Legendre over the radial
// ranks at 2^15 values of x (x = R at radial rank k / 2^15), and the quantile table inverts it
// linearly; beyond rank 1 - 2^-8 each tail probability down to 1e-12 (a 2^19 x 2^19 surface's most
// extreme rank) is solved for x and interpolated in log-log.
class TargetQuantiles final : public MarginalQuantile {
  public:
    // `samples`: how many projections are matched (ranks are clamped to their extreme order
    // statistics, 0.5 / samples from either end). The NDF must be shape-invariant.
    TargetQuantiles(const Ndf& ndf, std::size_t samples);
    float operator()(double u) const override;

  private:
    static constexpr int kSize = 1 << 17, kGrid = 1 << 15, kRadii = 1 << 14;
    static constexpr double kMaxS = 30;
    static constexpr double kTailStart = 1.0 / 256;
    // x with P(|X| > x) = tau, tau <= kTailStart (log-log interpolation, clamped at 1e-12).
    double tail(double tau) const;
    double edge_;
    std::vector<float> table_;
    std::vector<double> tail_log_tau_, tail_log_x_;
};

} // namespace gonio
