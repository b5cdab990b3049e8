#include "gonio/io/simulation_result.h"

#include "core/batch_means.h"
#include "core/check.h"

namespace gonio {

namespace {

Estimate estimate(const std::vector<std::string>& dims, const std::vector<size_t>& shape,
                  const std::string& units, const std::string& long_name) {
    return {Array(dims, shape, units, long_name),
            Array(dims, shape, units, "standard error of the " + long_name)};
}

// Orders from..to-1 of values stored [order][n], summed (one order: that order alone).
std::vector<double> orders_of(const std::vector<double>& v, int orders, int from, int to) {
    return sum_orders(v, 1, orders, from, to);
}

// The same sum of batches stored [batch][order][n], and its standard error (batch means).
std::vector<double> orders_stderr(const std::vector<double>& batches, int B, int orders, int from,
                                  int to) {
    return batch_stderr(sum_orders(batches, B, orders, from, to), B);
}

} // namespace

SimulationResult::SimulationResult(std::vector<double> theta_i_deg, std::vector<double> phi_i_deg,
                                   const BeckersSensor& sensor)
    : theta_i_deg_(std::move(theta_i_deg)), phi_i_deg_(std::move(phi_i_deg)) {
    projected_solid_angle_ = sensor.projected_solid_angles();
}

void SimulationResult::allocate(const TraceResult& r, const std::vector<Comparison>& models,
                                bool ensemble) {
    orders_ = r.orders;
    const size_t nt = theta_i_deg_.size(), np = phi_i_deg_.size(), no = size_t(r.orders),
                 ncell = size_t(r.cells), nc = size_t(r.channels);
    GONIO_CHECK_MSG(ncell == projected_solid_angle_.size(), "a trace on another sensor");
    filled_.assign(nt * np, false);
    stop.assign(nt * np, StopReason::rays);
    const std::vector<std::string> per_order_cell{"theta_i", "phi_i", "order", "cell", "channel"},
        per_order{"theta_i", "phi_i", "order", "channel"},
        per_cell{"theta_i", "phi_i", "cell", "channel"}, per_channel{"theta_i", "phi_i", "channel"},
        per_incidence{"theta_i", "phi_i"};
    const std::vector<size_t> s5{nt, np, no, ncell, nc}, s4o{nt, np, no, nc}, s4{nt, np, ncell, nc},
        s3{nt, np, nc}, s2{nt, np};
    auto side = [&](SimulatedSide& s, const std::string& what) {
        s.distribution =
            estimate(per_order_cell, s5, "1/sr", "simulated " + what + " per bounce order, cells");
        s.order_energy = estimate(per_order, s4o, "1",
                                  "fraction of the incident power per bounce order (" + what + ")");
        s.first = estimate(per_cell, s4, "1/sr", "simulated single-bounce " + what);
        s.higher = estimate(per_cell, s4, "1/sr", "simulated multiple-bounce " + what);
        s.all = estimate(per_cell, s4, "1/sr", "simulated " + what + ", all orders");
        s.first_albedo =
            estimate(per_channel, s3, "1", "simulated single-bounce albedo (" + what + ")");
        s.second_albedo =
            estimate(per_channel, s3, "1", "simulated second-order albedo (" + what + ")");
        s.higher_albedo =
            estimate(per_channel, s3, "1", "simulated multiple-bounce albedo (" + what + ")");
        s.all_albedo =
            estimate(per_channel, s3, "1", "simulated albedo, all orders (" + what + ")");
    };
    side(reflected, "BRDF");
    if (!r.transmitted.empty())
        side(transmitted, "BTDF, lower sensor (cell k mirrors upper cell k)");
    absorbed = estimate(per_channel, s3, "1", "fraction absorbed by the facets");
    capped = estimate(per_channel, s3, "1", "fraction cut by the bounce cap");
    lost = estimate(per_channel, s3, "1", "fraction lost (crack or endless ray): should be 0");
    unaccounted = Array(per_channel, s3, "1",
                        "1 - (reflected + transmitted + absorbed + capped + lost): zero to "
                        "round-off");
    rays = Array(per_incidence, s2, "1", "rays traced");
    segments = Array(per_incidence, s2, "1", "ray segments (rtcIntersect1 calls)");
    seconds = Array(per_incidence, s2, "s", "wall time of the tracing");
    rounds = Array(per_incidence, s2, "1", "rounds of rays given to every batch");
    realisations =
        Array(per_incidence, s2, "1", "independent surfaces the incidence was traced on");
    achieved_error =
        Array(per_incidence, s2, "1",
              "the accuracy target's relative standard error when the run stopped (-1: no target)");
    error_scope = ensemble ? ErrorScope::rays_and_surface : ErrorScope::rays;
    if (ensemble) {
        auto share = [&](const std::string& what) {
            return Array(per_channel, s3, "1", "the surfaces' share of the variance of " + what);
        };
        share_l1_albedo = share("the L1 albedo");
        share_l2plus_albedo = share("the L2+ albedo");
        share_linf_albedo = share("the L-infinity albedo");
        share_l1_cells = share("the L1 BRDF (median over the cells >= 0.1 of the peak)");
        share_linf_cells = share("the L-infinity BRDF (median over the cells >= 0.1 of the peak)");
    }
    auto comparison = [&] {
        ComparisonArrays c;
        c.relative_difference = estimate(per_channel, s3, "1", "relative difference of albedos");
        c.distance = estimate(per_channel, s3, "1", "relative L1 distance of the cells");
        c.sigmas = Array(per_channel, s3, "1", "albedo difference in standard errors");
        c.ratio = estimate(per_cell, s4, "1", "simulated / model per cell");
        return c;
    };
    comparisons.clear();
    for (const Comparison& m : models) {
        comparisons.push_back(comparison());
        if (!m.l2plus.empty()) comparisons.back().l2plus.push_back(comparison());
    }
}

void SimulationResult::put(size_t t, size_t p, const TraceResult& r,
                           const std::vector<Comparison>& models, const SurfaceShares* shares,
                           int surfaces) {
    if (done_ == 0) allocate(r, models, shares != nullptr);
    GONIO_CHECK_MSG((shares != nullptr) == (error_scope == ErrorScope::rays_and_surface),
                    "ensembles and single surfaces mixed");
    GONIO_CHECK(t < theta_i_deg_.size() && p < phi_i_deg_.size() && !filled_[index(t, p)]);
    GONIO_CHECK_MSG(r.orders == orders_ && models.size() == comparisons.size(),
                    "an incidence of another layout");
    const size_t nc = size_t(r.channels);
    const int B = r.batches, no = r.orders;
    auto brdf_of = [&](std::vector<double> v) {
        return cell_brdf(std::move(v), projected_solid_angle_, nc);
    };
    auto side = [&](SimulatedSide& s, const std::vector<double>& energy,
                    const std::vector<double>& energy_stderr, bool lower,
                    const std::vector<double>& order_energy,
                    const std::vector<double>& order_energy_stderr,
                    const std::vector<double>& order_batches) {
        const std::vector<double> dist = brdf_of(energy), dist_err = brdf_of(energy_stderr);
        s.distribution.mean.put({t, p}, dist);
        s.distribution.error.put({t, p}, dist_err);
        s.order_energy.mean.put({t, p}, order_energy);
        s.order_energy.error.put({t, p}, order_energy_stderr);
        s.first.mean.put({t, p}, orders_of(dist, no, 0, 1));
        s.first.error.put({t, p}, orders_of(dist_err, no, 0, 1));
        s.higher.mean.put({t, p}, orders_of(dist, no, 1, no));
        s.higher.error.put({t, p}, brdf_of(r.sum_stderr(1, no, lower)));
        s.all.mean.put({t, p}, orders_of(dist, no, 0, no));
        s.all.error.put({t, p}, brdf_of(r.sum_stderr(0, no, lower)));
        s.first_albedo.mean.put({t, p}, orders_of(order_energy, no, 0, 1));
        s.first_albedo.error.put({t, p}, orders_of(order_energy_stderr, no, 0, 1));
        if (no > 1) { // else no second order: zeros
            s.second_albedo.mean.put({t, p}, orders_of(order_energy, no, 1, 2));
            s.second_albedo.error.put({t, p}, orders_of(order_energy_stderr, no, 1, 2));
        }
        s.higher_albedo.mean.put({t, p}, orders_of(order_energy, no, 1, no));
        s.higher_albedo.error.put({t, p}, orders_stderr(order_batches, B, no, 1, no));
        s.all_albedo.mean.put({t, p}, orders_of(order_energy, no, 0, no));
        s.all_albedo.error.put({t, p}, orders_stderr(order_batches, B, no, 0, no));
    };
    side(reflected, r.energy, r.energy_stderr, false, r.ledger.reflected, r.ledger_stderr.reflected,
         r.ledger_batches.reflected);
    if (!transmitted.empty())
        side(transmitted, r.transmitted, r.transmitted_stderr, true, r.ledger.transmitted,
             r.ledger_stderr.transmitted, r.ledger_batches.transmitted);
    absorbed.mean.put({t, p}, r.ledger.absorbed);
    absorbed.error.put({t, p}, r.ledger_stderr.absorbed);
    capped.mean.put({t, p}, r.ledger.capped);
    capped.error.put({t, p}, r.ledger_stderr.capped);
    lost.mean.put({t, p}, r.ledger.lost);
    lost.error.put({t, p}, r.ledger_stderr.lost);
    unaccounted.put({t, p}, r.ledger.unaccounted);
    rays.at({t, p}) = double(r.rays);
    segments.at({t, p}) = double(r.segments);
    seconds.at({t, p}) = r.seconds;
    rounds.at({t, p}) = double(r.rounds);
    realisations.at({t, p}) = double(surfaces);
    if (shares) {
        share_l1_albedo.put({t, p}, shares->l1_albedo);
        share_l2plus_albedo.put({t, p}, shares->l2plus_albedo);
        share_linf_albedo.put({t, p}, shares->linf_albedo);
        share_l1_cells.put({t, p}, shares->l1_cells);
        share_linf_cells.put({t, p}, shares->linf_cells);
    }
    achieved_error.at({t, p}) = r.achieved_error;
    stop[index(t, p)] = r.stop;
    auto put_comparison = [&](ComparisonArrays& c, const Comparison& x) {
        c.relative_difference.mean.put({t, p}, x.relative_difference);
        c.relative_difference.error.put({t, p}, x.relative_difference_stderr);
        c.distance.mean.put({t, p}, x.distance);
        c.distance.error.put({t, p}, x.distance_stderr);
        c.sigmas.put({t, p}, x.sigmas);
        c.ratio.mean.put({t, p}, x.ratio);
        c.ratio.error.put({t, p}, x.ratio_stderr);
    };
    for (size_t m = 0; m < models.size(); ++m) {
        GONIO_CHECK(models[m].l2plus.size() == comparisons[m].l2plus.size());
        put_comparison(comparisons[m], models[m]);
        if (!models[m].l2plus.empty())
            put_comparison(comparisons[m].l2plus[0], models[m].l2plus[0]);
    }
    filled_[index(t, p)] = true;
    ++done_;
}

} // namespace gonio
