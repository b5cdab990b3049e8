#pragma once
// A model against the simulated quantity it models (L1 or every order), at one incidence, with the
// standard error of every figure: the simulation's from its batches, the model's from its own
// batches when it is a Monte Carlo estimate (the V-cavity) or else its quadrature tolerance, taken
// as an error bound. The two are independent, so their variances add.
#include "gonio/model/cell_model.h"
#include "gonio/trace/trace_result.h"

#include <vector>

namespace gonio {

// Per channel, except the maps (per cell and channel).
struct Comparison {
    std::vector<double> model_albedo; // the simulated albedos and their errors are in the trace
    // (sim - model) / model, and the difference over its standard error (how many sigmas).
    std::vector<double> relative_difference, relative_difference_stderr, sigmas;
    // sum |f_sim - f_model| Omega_perp / sum f_model Omega_perp (jackknife standard error).
    std::vector<double> distance, distance_stderr;
    // sim / model per cell (0 where the model is below 1e-12 of its brightest cell)
    std::vector<double> ratio, ratio_stderr;
    // A model of every order that knows its single scattering: its orders 2 and up against
    // simulated L2+ (one element), else empty.
    std::vector<Comparison> l2plus;
};

// The model against simulated L1, L-infinity or L2+, as `target` says.
Comparison compare_model(const TraceResult& sim, ModelTarget target, const ModelIncidence& model);
// The same for a model of the case: held against what it models and, when it models every order
// and knows its single scattering, its orders 2 and up against simulated L2+ as well.
Comparison compare_case_model(const TraceResult& sim, ModelTarget target,
                              const ModelIncidence& model);

} // namespace gonio
