#pragma once
// What a model gives over a case's sweep, as the result file stores it (gonio/pipeline/
// case_models.h evaluates it; gonio/io/result_writer.h writes it).
#include "core/named_array.h"

#include <string>

namespace gonio {

// One model over a case's sweep: arrays over theta_i, phi_i (theta_i major), cell and channel.
struct ModelResult {
    std::string name;          // "l1", "il", "vcavity", "ashikhmin", "pbrdf"
    std::string compared_with; // "l1" or "linf": the simulated BRDF it models
    std::string description;
    Array brdf;    // [theta_i, phi_i, cell, channel], 1/sr: cell averages
    Array energy;  // [theta_i, phi_i, cell, channel]: fraction of the incident power
    Array albedo;  // [theta_i, phi_i, channel]
    Array seconds; // [theta_i, phi_i]
    // Monte Carlo models (the V-cavity): standard errors of brdf and albedo (batch means), the
    // single-scattering part and the albedos of order 1, 2 and 2 and up.
    Array brdf_stderr, albedo_stderr;
    Array l1, l1_albedo, l2_albedo, l2plus_albedo;
};

} // namespace gonio
