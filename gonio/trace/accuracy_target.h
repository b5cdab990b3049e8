#pragma once
// A target accuracy instead of a ray count: the run adds rounds of rays to every batch until the
// relative standard error of the chosen quantity is at most `relative_error`, or a budget runs
// out. The quantities: an albedo (L1, L2+ or every order, the worst channel), or the per-cell
// BRDF (L1 or every order) over the cells at least `cell_fraction` of the brightest, the worst
// cell and channel.
#include "gonio/trace/trace_result.h"
#include "sensor/beckers_sensor.h"

#include <string>
#include <vector>

namespace gonio {

struct AccuracyTarget {
    std::string quantity = "l1_albedo"; // one of accuracy_target_quantities()
    double relative_error = 0;          // 0: no target (the ray count is used as given)
    double cell_fraction = 0.1;         // cells quantities: the cells that count
    long long max_rays = 10'000'000'000LL;
    double max_seconds = 3600;
    bool active() const { return relative_error > 0; }
};

const std::vector<std::string>& accuracy_target_quantities();

// The relative standard error of the target's quantity in `r` (0 where a quantity is exactly 0
// in every batch: more rays cannot change it).
double relative_error_of(const TraceResult& r, const AccuracyTarget& target,
                         const BeckersSensor& sensor);

} // namespace gonio
