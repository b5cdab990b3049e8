#pragma once
// How many surfaces an ensemble needs for an accuracy target (surface.realisations >= 2 with
// trace.target_error): Stein's two-stage procedure. The first pass traces every incidence on the
// configured surfaces; it is a pilot whose error only sizes the second pass (more surfaces, and
// more rays on each new one where the rays' share of the variance would still matter), which
// completes the ensemble and reports what it achieved. Iterating until the estimate falls below
// the target would keep the runs whose error was underestimated: with few surfaces' degrees of
// freedom, their errors read ~22 % too small.
#include "gonio/trace/accuracy_target.h"
#include "gonio/trace/trace_result.h"

#include <functional>

namespace gonio {

// One incidence's ensemble after a pass.
struct EnsembleStatus {
    int passes = 1;            // passes done, this one included
    int realisations = 1;      // surfaces traced so far
    long long rays = 0;        // rays traced so far, over every surface
    long long per_surface = 0; // rays each new surface is traced with
    double error = -1;         // the target quantity's relative standard error
    double elapsed = 0;        // seconds since the case's tracing began
};

// What to do next: stop (and why), or trace until `wanted` surfaces, `per_surface` rays each.
struct EnsembleStep {
    bool done = true;
    StopReason stop = StopReason::rays;
    int wanted = 0;
    long long per_surface = 0;
};

// `surface_share()`: the surfaces' share of the target quantity's variance (asked only when the
// pilot sizes the ensemble).
EnsembleStep plan_ensemble(const AccuracyTarget& target, int max_realisations,
                           const EnsembleStatus& status,
                           const std::function<double()>& surface_share);

} // namespace gonio
