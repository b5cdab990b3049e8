#pragma once
// What a model gives over a case's sweep, as the result file stores it: each incidence's
// ModelIncidence (gonio/model/cell_model.h) put in its place, in any order.
#include "core/named_array.h"
#include "gonio/model/cell_model.h"
#include "sensor/beckers_sensor.h"

#include <string>

namespace gonio {

// One model over a case's sweep: arrays over theta_i, phi_i (theta_i major), cell and channel.
struct ModelResult {
    std::string name; // the model kind's ("l1", "il", "vcavity", "ashikhmin", "pbrdf")
    ModelTarget compared_with = ModelTarget::l1;
    std::string description;
    Array brdf;    // [theta_i, phi_i, cell, channel], 1/sr: cell averages
    Array energy;  // [theta_i, phi_i, cell, channel]: fraction of the incident power
    Array albedo;  // [theta_i, phi_i, channel]
    Array seconds; // [theta_i, phi_i]
    // Monte Carlo models (the V-cavity): standard errors of brdf and albedo (batch means), the
    // single-scattering part and the albedos of order 1, 2 and 2 and up.
    Array brdf_stderr, albedo_stderr;
    Array l1, l1_albedo, l2_albedo, l2plus_albedo;
    // Analytic models: the largest relative error bound their quadrature reached over the sweep
    // (the configured tolerance unless a cell ran out of pieces first).
    double tolerance_reached = 0;

    // The arrays of an n_theta x n_phi sweep on `cells` cells and `channels` channels.
    void allocate(size_t n_theta, size_t n_phi, size_t cells, size_t channels, bool monte_carlo);
    // Incidence (t, p) of the sweep; `projected_solid_angle` per cell turns energies into BRDFs.
    void put(size_t t, size_t p, const ModelIncidence& m,
             const std::vector<double>& projected_solid_angle);
    // The seconds over the sweep (the phase model_<name>).
    double total_seconds() const;
};

} // namespace gonio
