#pragma once
// The simulation of one case over its sweep, as the result file stores it: typed arrays with
// named dimensions (core/named_array.h) over theta_i, phi_i, order, cell and channel, each with
// its standard error, and each model's comparison with the simulation. Every derived quantity
// (L1, L2+ and L-infinity maps and albedos, their transmitted counterparts and all their errors)
// is computed here, once, from each incidence's trace and its batches.
#include "core/enum_names.h"
#include "core/named_array.h"
#include "gonio/model/model_comparison.h"
#include "gonio/trace/trace_result.h"
#include "sensor/beckers_sensor.h"

#include <string>
#include <vector>

namespace gonio {

// What the standard errors include: the rays on one surface (conditional on it), or the rays and
// the surfaces of an ensemble (the error of the NDF's BSDF).
enum class ErrorScope { rays, rays_and_surface };
template <>
struct EnumNames<ErrorScope> {
    static constexpr const char* what = "error scope";
    static constexpr const char* names[] = {"rays", "rays+surface"};
};

// A Monte Carlo figure: the mean and its standard error (batch means), of the same layout.
struct Estimate {
    Array mean, error;
    bool empty() const { return mean.empty(); }
};

// One side of the sample: reflection (upper sensor) or transmission (lower sensor).
struct SimulatedSide {
    // [theta_i, phi_i, order, cell, channel], 1/sr: cell averages E_c / projected solid angle.
    Estimate distribution;
    // [theta_i, phi_i, order, channel]: fraction of the incident power per order.
    Estimate order_energy;
    // [theta_i, phi_i, cell, channel], 1/sr: single, multiple (2 and up) and every order.
    Estimate first, higher, all;
    // [theta_i, phi_i, channel]: albedos of order 1, order 2, orders 2 and up, every order.
    Estimate first_albedo, second_albedo, higher_albedo, all_albedo;
    bool empty() const { return distribution.empty(); }
};

// One model against the simulated quantity it models, over the sweep.
struct ComparisonArrays {
    Estimate relative_difference, distance; // [theta_i, phi_i, channel]
    Array sigmas;                           // [theta_i, phi_i, channel]
    Estimate ratio;                         // [theta_i, phi_i, cell, channel]
    std::vector<ComparisonArrays> l2plus;   // its orders 2 and up against simulated L2+
};

class SimulationResult {
  public:
    SimulationResult() = default;
    // A sweep of n_theta x n_phi incidences (theta_i major) on `sensor`'s cells.
    SimulationResult(std::vector<double> theta_i_deg, std::vector<double> phi_i_deg,
                     const BeckersSensor& sensor);

    // Puts incidence (t, p)'s trace and its models' comparisons (in the case's model order), in
    // any order of the incidences. An ensemble's trace (its batches are the surfaces) comes with
    // its surfaces' variance shares and their number.
    void put(size_t t, size_t p, const TraceResult& r, const std::vector<Comparison>& models,
             const SurfaceShares* shares = nullptr, int realisations = 1);
    // Incidences put so far, and whether the sweep is complete.
    size_t incidences() const { return done_; }
    bool complete() const { return done_ == theta_i_deg_.size() * phi_i_deg_.size(); }
    bool has(size_t t, size_t p) const { return !filled_.empty() && filled_[index(t, p)]; }
    int orders() const { return orders_; } // K + 1: orders 1..K, then "K+1 or more"
    const std::vector<double>& projected_solid_angle() const { return projected_solid_angle_; }

    SimulatedSide reflected, transmitted; // transmitted: transmissive materials only
    Estimate absorbed, capped, lost;      // [theta_i, phi_i, channel]
    Array unaccounted;                    // [theta_i, phi_i, channel]
    Array rays, segments, seconds, rounds, achieved_error; // [theta_i, phi_i]
    std::vector<StopReason> stop;                          // per incidence, theta_i major
    ErrorScope error_scope = ErrorScope::rays;
    Array realisations; // [theta_i, phi_i]: surfaces each incidence was traced on
    // Ensembles: the surfaces' share of each variance [theta_i, phi_i, channel]
    // (surface_ensemble.h).
    Array share_l1_albedo, share_l2plus_albedo, share_linf_albedo, share_l1_cells, share_linf_cells;
    std::vector<ComparisonArrays> comparisons; // per model of the case
    std::string surface;                       // where the surface came from (cache path, input)

  private:
    void allocate(const TraceResult& r, const std::vector<Comparison>& models, bool ensemble);
    size_t index(size_t t, size_t p) const { return t * phi_i_deg_.size() + p; }

    std::vector<double> theta_i_deg_, phi_i_deg_, projected_solid_angle_;
    int orders_ = 0;
    size_t done_ = 0;
    std::vector<bool> filled_; // per incidence
};

} // namespace gonio
