#include "gonio/trace/batch_tally.h"

#include "core/batch_means.h"

namespace gonio {

void BlockOutput::clear(int channels) {
    bin.clear(), exit.clear(), weight.clear();
    absorbed.assign(size_t(channels), 0.0), capped.assign(size_t(channels), 0.0);
    lost.assign(size_t(channels), 0.0);
    segments = 0;
}

BatchTally::BatchTally(int batches, int orders, int cells, int channels, bool transmits)
    : batches_(batches), orders_(orders), cells_(cells), nc_(channels), transmits_(transmits) {
    const size_t map = size_t(orders) * size_t(cells) * size_t(channels), B = size_t(batches);
    energy_.assign(B * map, 0.0);
    if (transmits) transmitted_.assign(B * map, 0.0), through_.assign(B * orders * nc_, 0.0);
    reflected_.assign(B * orders * nc_, 0.0);
    absorbed_.assign(B * nc_, 0.0), capped_.assign(B * nc_, 0.0), lost_.assign(B * nc_, 0.0);
    rays_.assign(B, 0);
}

void BatchTally::merge(int b, const BlockOutput& o, long long rays) {
    const size_t map = size_t(orders_) * cells_ * nc_, upper = size_t(orders_) * cells_;
    double* energy = energy_.data() + size_t(b) * map;
    double* transmitted = transmits_ ? transmitted_.data() + size_t(b) * map : nullptr;
    double* reflected = reflected_.data() + size_t(b) * orders_ * nc_;
    double* through = transmits_ ? through_.data() + size_t(b) * orders_ * nc_ : nullptr;
    for (size_t e = 0; e < o.bin.size(); ++e) {
        const bool up = size_t(o.bin[e]) < upper;
        const size_t bin = up ? size_t(o.bin[e]) : size_t(o.bin[e]) - upper, order = bin / cells_;
        double* map_sum = up ? energy : transmitted;
        double* order_sum = up ? reflected : through;
        for (int k = 0; k < nc_; ++k) {
            map_sum[bin * nc_ + k] += o.weight[e * nc_ + k];
            order_sum[order * nc_ + k] += o.weight[e * nc_ + k];
        }
    }
    for (int k = 0; k < nc_; ++k) {
        absorbed_[size_t(b) * nc_ + k] += o.absorbed[k];
        capped_[size_t(b) * nc_ + k] += o.capped[k];
        lost_[size_t(b) * nc_ + k] += o.lost[k];
    }
    rays_[size_t(b)] += rays;
    segments_ += o.segments;
}

TraceResult BatchTally::finish() const {
    TraceResult res;
    const int B = batches_, nc = nc_;
    res.orders = orders_, res.cells = cells_, res.channels = nc, res.batches = B;
    res.segments = segments_;
    for (long long n : rays_) res.rays += n;
    // Each batch divided by its ray count: the batch's own estimate.
    auto per_batch = [&](const std::vector<double>& sums) {
        std::vector<double> v(sums);
        const size_t n = v.size() / size_t(B);
        for (int b = 0; b < B; ++b) {
            const double scale = rays_[size_t(b)] > 0 ? 1.0 / double(rays_[size_t(b)]) : 0.0;
            for (size_t i = 0; i < n; ++i) v[size_t(b) * n + i] *= scale;
        }
        return v;
    };
    res.energy_batches = per_batch(energy_);
    if (transmits_) res.transmitted_batches = per_batch(transmitted_);
    res.ledger_batches.reflected = per_batch(reflected_);
    if (transmits_) res.ledger_batches.transmitted = per_batch(through_);
    res.ledger_batches.absorbed = per_batch(absorbed_),
    res.ledger_batches.capped = per_batch(capped_);
    res.ledger_batches.lost = per_batch(lost_);
    complete(res, transmits_);
    return res;
}

void BatchTally::complete(TraceResult& res, bool transmits) {
    const int B = res.batches, nc = res.channels, orders = res.orders;
    res.energy = batch_mean(res.energy_batches, B);
    res.energy_stderr = batch_stderr(res.energy_batches, B);
    if (transmits) {
        res.transmitted = batch_mean(res.transmitted_batches, B);
        res.transmitted_stderr = batch_stderr(res.transmitted_batches, B);
    }
    // The ledger, its batches and its errors; unaccounted closes each batch.
    EnergyLedger& all = res.ledger_batches;
    all.unaccounted.assign(size_t(B) * nc, 1.0);
    for (int b = 0; b < B; ++b)
        for (int k = 0; k < nc; ++k) {
            double& u = all.unaccounted[size_t(b) * nc + k];
            for (int order = 0; order < orders; ++order) {
                u -= all.reflected[(size_t(b) * orders + order) * nc + k];
                if (transmits) u -= all.transmitted[(size_t(b) * orders + order) * nc + k];
            }
            u -= all.absorbed[size_t(b) * nc + k] + all.capped[size_t(b) * nc + k] +
                 all.lost[size_t(b) * nc + k];
        }
    for (auto entry :
         {&EnergyLedger::reflected, &EnergyLedger::transmitted, &EnergyLedger::absorbed,
          &EnergyLedger::capped, &EnergyLedger::lost, &EnergyLedger::unaccounted}) {
        const std::vector<double>& v = all.*entry;
        if (v.empty()) continue;
        res.ledger.*entry = batch_mean(v, B);
        res.ledger_stderr.*entry = batch_stderr(v, B);
    }
}

} // namespace gonio
