#include "gonio/io/simulation_result.h"

#include "core/batch_means.h"

namespace gonio {

namespace {

void append(std::vector<double>& to, const std::vector<double>& v) {
    to.insert(to.end(), v.begin(), v.end());
}

// One side of a trace: its means, and the errors of sums over orders taken batch by batch.
void append_side(SimulatedSide& side, const TraceResult& r, const std::vector<double>& energy,
                 const std::vector<double>& energy_stderr, const std::vector<double>& batches,
                 const std::vector<double>& order_energy,
                 const std::vector<double>& order_energy_stderr,
                 const std::vector<double>& order_batches) {
    const int B = r.batches, no = r.orders;
    append(side.energy, energy), append(side.energy_stderr, energy_stderr);
    append(side.order_energy, order_energy), append(side.order_energy_stderr, order_energy_stderr);
    append(side.higher_stderr, batch_stderr(sum_orders(batches, B, no, 1, no), B));
    append(side.all_stderr, batch_stderr(sum_orders(batches, B, no, 0, no), B));
    append(side.higher_albedo_stderr, batch_stderr(sum_orders(order_batches, B, no, 1, no), B));
    append(side.all_albedo_stderr, batch_stderr(sum_orders(order_batches, B, no, 0, no), B));
}

void append(Comparison& to, const Comparison& c) {
    for (auto field :
         {&Comparison::sim_albedo, &Comparison::sim_albedo_stderr, &Comparison::model_albedo,
          &Comparison::model_albedo_stderr, &Comparison::relative_difference,
          &Comparison::relative_difference_stderr, &Comparison::sigmas, &Comparison::distance,
          &Comparison::distance_stderr, &Comparison::ratio, &Comparison::ratio_stderr})
        append(to.*field, c.*field);
}

} // namespace

void SimulationResult::append(const TraceResult& r, const std::vector<Comparison>& models) {
    append_side(reflected, r, r.energy, r.energy_stderr, r.energy_batches, r.ledger.reflected,
                r.ledger_stderr.reflected, r.ledger_batches.reflected);
    if (!r.transmitted.empty())
        append_side(transmitted, r, r.transmitted, r.transmitted_stderr, r.transmitted_batches,
                    r.ledger.transmitted, r.ledger_stderr.transmitted,
                    r.ledger_batches.transmitted);
    using gonio::append;
    append(absorbed, r.ledger.absorbed), append(absorbed_stderr, r.ledger_stderr.absorbed);
    append(capped, r.ledger.capped), append(capped_stderr, r.ledger_stderr.capped);
    append(lost, r.ledger.lost), append(lost_stderr, r.ledger_stderr.lost);
    append(unaccounted, r.ledger.unaccounted);
    rays.push_back(double(r.rays));
    segments.push_back(double(r.segments));
    seconds.push_back(r.seconds);
    rounds.push_back(double(r.rounds));
    achieved_error.push_back(r.achieved_error);
    stop.push_back(r.stop);
    comparisons.resize(models.size());
    for (size_t m = 0; m < models.size(); ++m) append(comparisons[m], models[m]);
}

} // namespace gonio
