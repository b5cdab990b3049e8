#pragma once
// What a Monte Carlo beam (the simulator, the V-cavity estimator) reports: the exits per order and
// sensor cell, the energy ledger, each as the mean of B independent batches with its standard
// error, and the batches themselves for the errors of derived quantities (core/batch_means.h).
#include "core/enum_names.h"

#include <string>
#include <vector>

namespace gonio {

// How a trace (or an ensemble's passes) ended: the rays asked for; the accuracy target met (or,
// for an ensemble's sized pass, not met); or a budget of the target spent first.
enum class StopReason { rays, target, target_not_met, max_rays, max_seconds, max_realisations };
template <>
struct EnumNames<StopReason> {
    static constexpr const char* what = "stop reason";
    static constexpr const char* names[] = {"rays",     "target",      "target_not_met",
                                            "max_rays", "max_seconds", "max_realisations"};
};

// Fractions of the incident power, per channel.
struct EnergyLedger {
    std::vector<double> reflected;   // [order][channel]: orders 1..K, then the overflow order
    std::vector<double> transmitted; // [order][channel]: transmissive materials only, else empty
    std::vector<double> absorbed;    // [channel]
    std::vector<double> capped;      // [channel]: still bouncing at max_bounces
    std::vector<double> lost;        // [channel]: crossed an opaque surface, or wrapped without
                                     // end (a crack or a numerical failure)
    // 1 - everything above, per channel: zero up to round-off when nothing is lost.
    std::vector<double> unaccounted;
};

// Per batch, the bounce orders summed as the errors of every derived quantity need them (the
// multiple- and all-order maps of the result file, the models' comparisons, the accuracy target,
// an ensemble's ray variance): [batch][cell][channel], each summed from 0 in order as
// sum_orders (core/batch_means.h) does. Three maps a batch whatever the orders kept.
struct OrderSums {
    std::vector<double> l1, l2plus, linf;
    bool empty() const { return l1.empty(); }
};

struct TraceResult {
    int orders = 0; // K + 1 (the last is the overflow order)
    int cells = 0, channels = 0;
    long long rays = 0;
    long long segments = 0;     // rtcIntersect1 calls
    std::vector<double> energy; // [order][cell][channel]: fraction of the incident power
    // The same on the lower sensor, for transmissive materials (empty otherwise). The order of a
    // transmitted ray is its number of scattering events, refractions included.
    std::vector<double> transmitted;
    EnergyLedger ledger;
    double seconds = 0;

    // Standard errors of the above, from the batches.
    int batches = 0;
    std::vector<double> energy_stderr, transmitted_stderr;
    EnergyLedger ledger_stderr;
    // The batches' order sums, and their ledgers ([batch][order][channel]: small).
    OrderSums energy_sums, transmitted_sums;
    EnergyLedger ledger_batches;
    // The batches' own estimates per order, [batch][order][cell][channel]: kept only by a batch
    // shard (combine_batch_shards needs them); every other trace reduces each batch as it closes.
    std::vector<double> energy_batches, transmitted_batches;

    // The standard errors of the order sums, [cell][channel]: what a unit keeps of them once its
    // comparisons are made (drop_order_sums).
    OrderSums sums_stderr, transmitted_sums_stderr;

    // The batch sums of orders from..to-1 of the upper (or lower) sensor: L1 (0, 1), L2+ (1,
    // orders) or every order (0, orders).
    const std::vector<double>& sum_batches(int from, int to, bool lower = false) const;
    // Their standard error, from the batches or, once dropped, as kept.
    std::vector<double> sum_stderr(int from, int to, bool lower = false) const;
    // Keeps the order sums' errors and frees the sums (B maps each).
    void drop_order_sums();

    StopReason stop = StopReason::rays; // how the run ended
    long long rounds = 1;               // passes over every batch
    double achieved_error = -1; // the target quantity's relative standard error (-1: no target)
};

// An ensemble of surfaces (gonio/run/surface_ensemble.h): the surfaces' share of the variance,
// per channel: of the L1, L2+ and L-infinity albedos, and the median over the cells whose L1 (resp.
// L-infinity) BRDF is at least a tenth of the peak.
struct SurfaceShares {
    std::vector<double> l1_albedo, l2plus_albedo, linf_albedo, l1_cells, linf_cells;
};

} // namespace gonio
