#pragma once
// The simulation of one case over its sweep (theta_i major, then phi_i), as the result file
// stores it: means with their standard errors, and each model's comparison with the simulation.
#include "gonio/model/model_comparison.h"
#include "gonio/trace/trace_result.h"

#include <string>
#include <vector>

namespace gonio {

// One side of the sample: reflection (upper sensor) or transmission (lower sensor).
struct SimulatedSide {
    std::vector<double> energy, energy_stderr;             // [theta_i][phi_i][order][cell][channel]
    std::vector<double> order_energy, order_energy_stderr; // [theta_i][phi_i][order][channel]
    // Standard errors of orders 2 and up and of every order: per cell [theta_i][phi_i][cell]
    // [channel] and summed over the cells [theta_i][phi_i][channel].
    std::vector<double> higher_stderr, all_stderr, higher_albedo_stderr, all_albedo_stderr;
    bool empty() const { return energy.empty(); }
};

struct SimulationResult {
    int orders = 0;                       // K + 1: orders 1..K, then "K+1 or more"
    SimulatedSide reflected, transmitted; // transmitted: transmissive materials only
    std::vector<double> absorbed, capped, lost, unaccounted; // [theta_i][phi_i][channel]
    std::vector<double> absorbed_stderr, capped_stderr, lost_stderr;
    std::vector<double> rays, segments, seconds, rounds, achieved_error; // [theta_i][phi_i]
    std::vector<std::string> stop;                                       // [theta_i][phi_i]
    std::vector<Comparison> comparisons; // per model of the case, over the sweep
    std::string surface;                 // where the surface came from (cache path, input)

    // Appends one incidence's trace and its models' comparisons (in the case's model order).
    void append(const TraceResult& r, const std::vector<Comparison>& models);
};

} // namespace gonio
