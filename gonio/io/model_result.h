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
    // Monte Carlo models (the V-cavity, the Smith random walk): standard errors of brdf and albedo
    // (batch means), the second-order albedo.
    Array brdf_stderr, albedo_stderr, l2_albedo;
    // Models that know their single scattering (the Monte Carlo ones, the compensated ones): it
    // and the rest, per cell [theta_i, phi_i, cell, channel] and in albedo [theta_i, phi_i,
    // channel], and (Monte Carlo) the albedos of orders 1, 2, 3+ [theta_i, phi_i, model_order,
    // channel], reflected and transmitted (transmissive facets), with their standard errors.
    Array l1, l2plus, l1_albedo, l2plus_albedo;
    Array l2plus_stderr; // Monte Carlo: the standard error of l2plus (batch means)
    Array order_albedo, order_albedo_stderr, order_transmittance, order_transmittance_stderr;
    // Analytic models: the largest relative error bound their quadrature reached over the sweep
    // (the configured tolerance unless a cell ran out of pieces first).
    double tolerance_reached = 0;

    // The arrays of an n_theta x n_phi sweep on `cells` cells and `channels` channels, for records
    // like `first` (Monte Carlo or not, with orders or not, transmitting or not).
    void allocate(size_t n_theta, size_t n_phi, size_t cells, size_t channels,
                  const ModelIncidence& first);
    // Incidence (t, p) of the sweep; `projected_solid_angle` per cell turns energies into BRDFs.
    void put(size_t t, size_t p, const ModelIncidence& m,
             const std::vector<double>& projected_solid_angle);
    // The seconds over the sweep (the phase model_<name>).
    double total_seconds() const;
};

} // namespace gonio
