#pragma once
// One incidence traced on an ensemble of independent surfaces (surface.realisations = R >= 2).
// Each surface's trace is kept as its means (its batches only give the rays' variance), and the
// ensemble is one TraceResult whose batches are the R surface means: batch means over them
// estimate the variance of the ensemble mean, rays and surfaces together, without bias for any R
// >= 2 and whatever the rays per surface (unequal counts included: the means are independent and
// unbiased for the same BSDF, so s^2 / R is unbiased for the variance of their average). Every
// downstream error (sums over orders, the models' comparison, the accuracy target) is then taken
// over the surfaces, with R - 1 degrees of freedom.
//
// The split of that variance: the rays' part is (1 / R^2) sum_r se_r^2, with se_r each surface's
// own standard error from its batches; the surfaces' part is the rest (clipped at 0).
#include "gonio/trace/accuracy_target.h"
#include "gonio/trace/trace_result.h"
#include "sensor/beckers_sensor.h"

#include <vector>

namespace gonio {

class IncidenceEnsemble {
  public:
    // Adds the trace of the next surface (batches used for its rays' variance, then dropped).
    void add(TraceResult trace);
    int realisations() const { return int(surfaces_.size()); }
    long long rays() const;

    // The ensemble as one trace: means over the surfaces, and the surfaces as its batches.
    TraceResult combined() const;
    SurfaceShares shares(const TraceResult& combined, const BeckersSensor& sensor) const;
    // The surfaces' share of the target quantity's variance (its worst channel or cell summary).
    double target_share(const TraceResult& combined, const AccuracyTarget& target,
                        const BeckersSensor& sensor) const;

  private:
    // The rays' variance of one surface's means of the shared quantities.
    struct RayVariance {
        std::vector<double> l1_albedo, l2plus_albedo, linf_albedo; // [channel]
        std::vector<double> l1_cells, linf_cells;                  // [cell][channel]
    };
    struct Surface {
        TraceResult mean; // batches dropped
        RayVariance variance;
    };
    std::vector<Surface> surfaces_;
};

} // namespace gonio
