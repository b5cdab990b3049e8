#include "gonio/run/surface_ensemble.h"

#include "core/batch_means.h"
#include "core/buffer_pool.h"
#include "core/check.h"
#include "gonio/trace/batch_reducer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {
std::vector<double> squared(std::vector<double> v) {
    for (double& x : v) x *= x;
    return v;
}
// The variance (squared batch standard error) of orders from..to-1 summed, per [n].
std::vector<double> ray_variance(const std::vector<double>& batches, int B, int orders, int from,
                                 int to) {
    return squared(batch_stderr(sum_orders(batches, B, orders, from, to), B));
}
// A surface's share of a variance: what the rays do not explain.
double share(double total, double rays) {
    return total > 0 ? std::max(0.0, 1.0 - rays / total) : 0.0;
}
double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
} // namespace

void IncidenceEnsemble::add(TraceResult t) {
    const int B = t.batches, no = t.orders;
    Surface s;
    s.variance.l1_albedo = ray_variance(t.ledger_batches.reflected, B, no, 0, 1);
    s.variance.l2plus_albedo = ray_variance(t.ledger_batches.reflected, B, no, 1, no);
    s.variance.linf_albedo = ray_variance(t.ledger_batches.reflected, B, no, 0, no);
    s.variance.l1_cells = squared(batch_stderr(t.sum_batches(0, 1), B));
    s.variance.linf_cells = squared(batch_stderr(t.sum_batches(0, no), B));
    // Freed, not just cleared: an ensemble keeps hundreds of these.
    for (auto v :
         {&t.energy_batches, &t.transmitted_batches, &t.energy_stderr, &t.transmitted_stderr})
        give_back(std::move(*v));
    for (OrderSums* sums : {&t.energy_sums, &t.transmitted_sums})
        for (auto field : {&OrderSums::l1, &OrderSums::l2plus, &OrderSums::linf})
            give_back(std::move(sums->*field));
    t.ledger_batches = EnergyLedger{};
    t.ledger_stderr = EnergyLedger{};
    s.mean = std::move(t);
    surfaces_.push_back(std::move(s));
}

long long IncidenceEnsemble::rays() const {
    long long n = 0;
    for (const Surface& s : surfaces_) n += s.mean.rays;
    return n;
}

TraceResult IncidenceEnsemble::combined() const {
    GONIO_CHECK_MSG(surfaces_.size() >= 2, "an ensemble needs two surfaces or more");
    const int R = int(surfaces_.size());
    TraceResult c;
    const TraceResult& first = surfaces_[0].mean;
    c.orders = first.orders, c.cells = first.cells, c.channels = first.channels;
    c.batches = R;
    for (const Surface& s : surfaces_) {
        c.rays += s.mean.rays, c.segments += s.mean.segments, c.seconds += s.mean.seconds;
        c.rounds = std::max(c.rounds, s.mean.rounds);
    }
    // Each mean array: the surfaces as batches, their mean and its standard error.
    auto fill = [&](auto field_mean, auto field_err, auto field_batches) {
        std::vector<double>& batches = field_batches(c);
        for (const Surface& s : surfaces_) {
            const std::vector<double>& m = field_mean(s.mean);
            batches.insert(batches.end(), m.begin(), m.end());
        }
        if (batches.empty()) return;
        field_mean(c) = batch_mean(batches, R);
        field_err(c) = batch_stderr(batches, R);
    };
    // The maps: the surfaces' means reduced as batches are (their order sums kept).
    auto maps = [&](std::vector<double> TraceResult::*mean, std::vector<double> TraceResult::*err,
                    OrderSums TraceResult::*sums) {
        if ((first.*mean).empty()) return;
        std::vector<double> batches;
        batches.reserve(size_t(R) * (first.*mean).size());
        for (const Surface& s : surfaces_)
            batches.insert(batches.end(), (s.mean.*mean).begin(), (s.mean.*mean).end());
        reduce_batches(batches, R, c.orders, size_t(c.channels), c.*mean, c.*err, c.*sums);
    };
    maps(&TraceResult::energy, &TraceResult::energy_stderr, &TraceResult::energy_sums);
    maps(&TraceResult::transmitted, &TraceResult::transmitted_stderr,
         &TraceResult::transmitted_sums);
    for (auto entry :
         {&EnergyLedger::reflected, &EnergyLedger::transmitted, &EnergyLedger::absorbed,
          &EnergyLedger::capped, &EnergyLedger::lost, &EnergyLedger::unaccounted})
        fill(
            [entry](auto& r) -> auto& { return r.ledger.*entry; },
            [entry](auto& r) -> auto& { return r.ledger_stderr.*entry; },
            [entry](auto& r) -> auto& { return r.ledger_batches.*entry; });
    return c;
}

SurfaceShares IncidenceEnsemble::shares(const TraceResult& c, const BeckersSensor& sensor) const {
    const int R = c.batches, no = c.orders;
    const size_t nc = size_t(c.channels);
    const double R2 = double(R) * double(R);
    auto ray_part = [&](std::vector<double> RayVariance::*field) {
        std::vector<double> sum = surfaces_[0].variance.*field;
        for (size_t r = 1; r < surfaces_.size(); ++r)
            for (size_t k = 0; k < sum.size(); ++k) sum[k] += (surfaces_[r].variance.*field)[k];
        for (double& v : sum) v /= R2;
        return sum;
    };
    auto albedo_shares = [&](int from, int to, std::vector<double> RayVariance::*field) {
        const std::vector<double> total = ray_variance(c.ledger_batches.reflected, R, no, from, to);
        const std::vector<double> rays = ray_part(field);
        std::vector<double> out(nc);
        for (size_t k = 0; k < nc; ++k) out[k] = share(total[k], rays[k]);
        return out;
    };
    // Per channel, the median share over the cells at least a tenth of the brightest.
    auto cell_shares = [&](int to, std::vector<double> RayVariance::*field) {
        const std::vector<double> total = squared(batch_stderr(c.sum_batches(0, to), R));
        const std::vector<double> mean = sum_orders(c.energy, 1, no, 0, to);
        const std::vector<double> rays = ray_part(field);
        std::vector<double> out(nc);
        const size_t cells = mean.size() / nc;
        auto brdf = [&](size_t i) {
            return mean[i] / sensor.cell(int(i / nc)).projected_solid_angle;
        };
        for (size_t k = 0; k < nc; ++k) {
            double peak = 0;
            for (size_t cell = 0; cell < cells; ++cell) peak = std::max(peak, brdf(cell * nc + k));
            std::vector<double> s;
            for (size_t cell = 0; cell < cells; ++cell) {
                const size_t i = cell * nc + k;
                if (peak > 0 && brdf(i) >= 0.1 * peak) s.push_back(share(total[i], rays[i]));
            }
            out[k] = median(s);
        }
        return out;
    };
    SurfaceShares s;
    s.l1_albedo = albedo_shares(0, 1, &RayVariance::l1_albedo);
    s.l2plus_albedo = albedo_shares(1, no, &RayVariance::l2plus_albedo);
    s.linf_albedo = albedo_shares(0, no, &RayVariance::linf_albedo);
    s.l1_cells = cell_shares(1, &RayVariance::l1_cells);
    s.linf_cells = cell_shares(no, &RayVariance::linf_cells);
    return s;
}

double IncidenceEnsemble::target_share(const TraceResult& c, const AccuracyTarget& target,
                                       const BeckersSensor& sensor) const {
    const SurfaceShares s = shares(c, sensor);
    using Q = TargetQuantity;
    const std::vector<double>& v = target.quantity == Q::l1_albedo       ? s.l1_albedo
                                   : target.quantity == Q::l2plus_albedo ? s.l2plus_albedo
                                   : target.quantity == Q::linf_albedo   ? s.linf_albedo
                                   : target.quantity == Q::l1_cells      ? s.l1_cells
                                                                         : s.linf_cells;
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

} // namespace gonio
