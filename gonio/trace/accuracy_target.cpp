#include "gonio/trace/accuracy_target.h"

#include "core/batch_means.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {
const Key kTargetError = Key::number("target_error", {0, 1, true, false},
                                     "an accuracy target instead of a ray count: rounds of "
                                     "`trace.rays` are added until the target quantity's relative "
                                     "standard error is at most this")
                             .note_default("—");
const Key kTarget =
    Key::string(
        "target", enum_names<TargetQuantity>(),
        "the target quantity (the worst channel; `*_cells`: the worst cell whose BRDF is at "
        "least `trace.target_cell_fraction` of the brightest)")
        .fallback("l1_albedo");
const Key kCellFraction = Key::number("target_cell_fraction", {0, 1, true, false},
                                      "`*_cells` targets: the cells that count")
                              .fallback(0.1);
const Key kMaxRays =
    Key::integer("max_rays", {1, 1e13},
                 "the target's ray budget: the run stops when the next round would "
                 "exceed it, and says so")
        .fallback(1e10)
        .noting("≥ `trace.rays`");
const Key kMaxSeconds =
    Key::number("max_seconds", {0, 1e7, true, false},
                "the target's time budget (the run then depends on the machine)")
        .fallback(3600.0);
} // namespace

std::vector<Key> accuracy_target_keys() {
    return {kTargetError, kTarget, kCellFraction, kMaxRays, kMaxSeconds};
}

AccuracyTarget read_accuracy_target(TableReader& r, long long rays) {
    AccuracyTarget t;
    t.quantity = enum_named<TargetQuantity>(r.string(kTarget));
    t.cell_fraction = r.number(kCellFraction);
    t.max_rays = r.integer(kMaxRays);
    t.max_seconds = r.number(kMaxSeconds);
    if (!r.has(kTargetError.name)) {
        for (const Key* k : {&kTarget, &kCellFraction, &kMaxRays, &kMaxSeconds})
            if (r.has(k->name)) r.fail(k->name, "applies only with trace.target_error");
        return t;
    }
    t.relative_error = r.number(kTargetError);
    if (t.max_rays < rays)
        r.fail("max_rays",
               "must be at least trace.rays (" + std::to_string(rays) + "), the rays of one round");
    return t;
}

double relative_error_of(const TraceResult& r, const AccuracyTarget& t,
                         const BeckersSensor& sensor) {
    const int B = r.batches, nc = r.channels, no = r.orders;
    using Q = TargetQuantity;
    const bool first_only = t.quantity == Q::l1_albedo || t.quantity == Q::l1_cells;
    const int from = t.quantity == Q::l2plus_albedo ? 1 : 0, to = first_only ? 1 : no;
    const bool albedo = t.quantity != Q::l1_cells && t.quantity != Q::linf_cells;
    // Per batch, the quantity's albedos [channel] or cell energies [cell][channel].
    const std::vector<double> x =
        albedo ? sum_orders(r.ledger_batches.reflected, B, no, from, to) : r.sum_batches(from, to);
    const std::vector<double> mean = batch_mean(x, B), err = batch_stderr(x, B);
    auto relative = [&](size_t i) { return mean[i] != 0 ? err[i] / std::abs(mean[i]) : 0.0; };
    double worst = 0;
    if (albedo) {
        for (size_t k = 0; k < size_t(nc); ++k) worst = std::max(worst, relative(k));
        return worst;
    }
    // The cells that count: BRDF (energy over projected solid angle) at least the fraction of
    // the brightest, per channel.
    auto brdf = [&](size_t i) {
        return mean[i] / sensor.cell(int(i / size_t(nc))).projected_solid_angle;
    };
    for (size_t k = 0; k < size_t(nc); ++k) {
        double peak = 0;
        for (size_t i = k; i < mean.size(); i += size_t(nc)) peak = std::max(peak, brdf(i));
        for (size_t i = k; i < mean.size(); i += size_t(nc))
            if (peak > 0 && brdf(i) >= t.cell_fraction * peak) worst = std::max(worst, relative(i));
    }
    return worst;
}

} // namespace gonio
