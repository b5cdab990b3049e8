#include "gonio/trace/batch_tally.h"

#include "core/batch_means.h"
#include "core/buffer_pool.h"
#include "core/check.h"

#include <algorithm>

namespace gonio {

void BlockOutput::clear(int channels) {
    bin.clear(), exit.clear(), weight.clear();
    absorbed.assign(size_t(channels), 0.0), capped.assign(size_t(channels), 0.0);
    lost.assign(size_t(channels), 0.0);
    segments = 0;
}

namespace {
// The ledger's means and errors from its batches; unaccounted closes each batch.
void complete_ledger(TraceResult& res, bool transmits) {
    const int B = res.batches, nc = res.channels, orders = res.orders;
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

double inverse(long long rays) {
    return rays > 0 ? 1.0 / double(rays) : 0.0;
}
} // namespace

BatchTally::BatchTally(int batches, int orders, int cells, int channels, bool transmits)
    : batches_(batches), orders_(orders), cells_(cells), nc_(channels), transmits_(transmits) {}

BatchTally::~BatchTally() {
    give_back(std::move(energy_)), give_back(std::move(transmitted_));
}

void BatchTally::keep(BatchKeeping k) {
    GONIO_CHECK_MSG(!allocated_, "a tally's keeping is chosen before its first merge");
    keep_ = k;
}

void BatchTally::allocate() {
    if (allocated_) return;
    allocated_ = true;
    const size_t n = size_t(cells_) * size_t(nc_), map = size_t(orders_) * n, B = size_t(batches_);
    const size_t kept = keep_ == BatchKeeping::stream ? 1 : B;
    energy_ = take_zeroed(kept * map);
    if (transmits_) transmitted_ = take_zeroed(kept * map), through_.assign(B * orders_ * nc_, 0.0);
    reflected_.assign(B * orders_ * nc_, 0.0);
    absorbed_.assign(B * nc_, 0.0), capped_.assign(B * nc_, 0.0), lost_.assign(B * nc_, 0.0);
    rays_.assign(B, 0);
    if (keep_ == BatchKeeping::stream) {
        energy_reducer_ = std::make_unique<BatchReducer>(batches_, orders_, cells_, nc_);
        if (transmits_)
            transmitted_reducer_ = std::make_unique<BatchReducer>(batches_, orders_, cells_, nc_);
        for (OpenRows& open : open_rows_) open.marked.assign(size_t(orders_) * cells_, 0);
    }
}

// Streaming: the open batch divided by its rays into the reducers (batches never opened, of no
// rays, as zeros before it), and its maps cleared for the next. Only the rows (an order's cell)
// its rays reached are worked on.
void BatchTally::close_open_batch() {
    if (open_ < 0) return;
    std::vector<std::uint32_t> none;
    for (; reduced_ < open_; ++reduced_) {
        energy_reducer_->add(nullptr, none);
        if (transmits_) transmitted_reducer_->add(nullptr, none);
    }
    const double scale = inverse(rays_[size_t(open_)]);
    for (int side = 0; side < (transmits_ ? 2 : 1); ++side) {
        std::vector<double>& map = side == 0 ? energy_ : transmitted_;
        BatchReducer& reducer = side == 0 ? *energy_reducer_ : *transmitted_reducer_;
        OpenRows& open = open_rows_[size_t(side)];
        for (std::uint32_t row : open.touched)
            for (size_t k = 0; k < size_t(nc_); ++k) map[row * size_t(nc_) + k] *= scale;
        reducer.add(map.data(), open.touched);
        for (std::uint32_t row : open.touched) {
            std::fill_n(&map[row * size_t(nc_)], size_t(nc_), 0.0);
            open.marked[row] = 0;
        }
        open.touched.clear();
    }
    reduced_ = open_ + 1;
    open_ = -1;
}

void BatchTally::merge(int b, const BlockOutput& o, long long rays) {
    allocate();
    const size_t map = size_t(orders_) * cells_ * nc_, upper = size_t(orders_) * cells_;
    size_t at = size_t(b) * map;
    if (keep_ == BatchKeeping::stream) {
        if (b != open_) {
            GONIO_CHECK_MSG(b > open_ && b >= reduced_, "a streaming tally's batches out of order");
            close_open_batch();
            open_ = b;
        }
        at = 0;
    }
    double* energy = energy_.data() + at;
    double* transmitted = transmits_ ? transmitted_.data() + at : nullptr;
    double* reflected = reflected_.data() + size_t(b) * orders_ * nc_;
    double* through = transmits_ ? through_.data() + size_t(b) * orders_ * nc_ : nullptr;
    for (size_t e = 0; e < o.bin.size(); ++e) {
        const bool up = size_t(o.bin[e]) < upper;
        const size_t bin = up ? size_t(o.bin[e]) : size_t(o.bin[e]) - upper, order = bin / cells_;
        double* map_sum = up ? energy : transmitted;
        double* order_sum = up ? reflected : through;
        if (keep_ == BatchKeeping::stream) {
            OpenRows& open = open_rows_[up ? 0 : 1];
            if (!open.marked[bin]) open.marked[bin] = 1, open.touched.push_back(std::uint32_t(bin));
        }
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

TraceResult BatchTally::finish() {
    allocate();
    TraceResult res;
    const int B = batches_;
    res.orders = orders_, res.cells = cells_, res.channels = nc_, res.batches = B;
    res.segments = segments_;
    for (long long n : rays_) res.rays += n;
    // Each batch divided by its ray count: the batch's own estimate.
    auto per_batch = [&](const std::vector<double>& sums) {
        std::vector<double> v(sums);
        const size_t n = v.size() / size_t(B);
        for (int b = 0; b < B; ++b) {
            const double scale = inverse(rays_[size_t(b)]);
            for (size_t i = 0; i < n; ++i) v[size_t(b) * n + i] *= scale;
        }
        return v;
    };
    res.ledger_batches.reflected = per_batch(reflected_);
    if (transmits_) res.ledger_batches.transmitted = per_batch(through_);
    res.ledger_batches.absorbed = per_batch(absorbed_),
    res.ledger_batches.capped = per_batch(capped_);
    res.ledger_batches.lost = per_batch(lost_);
    if (keep_ == BatchKeeping::stream) {
        GONIO_CHECK_MSG(energy_reducer_, "a streaming tally is finished once");
        close_open_batch();
        std::vector<std::uint32_t> none; // batches never opened: no rays
        for (; reduced_ < B; ++reduced_) {
            energy_reducer_->add(nullptr, none);
            if (transmits_) transmitted_reducer_->add(nullptr, none);
        }
        energy_reducer_->finish(res.energy, res.energy_stderr, res.energy_sums);
        if (transmits_)
            transmitted_reducer_->finish(res.transmitted, res.transmitted_stderr,
                                         res.transmitted_sums);
        energy_reducer_.reset(), transmitted_reducer_.reset();
        complete_ledger(res, transmits_);
        return res;
    }
    const size_t map = size_t(orders_) * cells_ * nc_;
    std::vector<double> scaled(map);
    auto reduce = [&](const std::vector<double>& sums, std::vector<double>& mean,
                      std::vector<double>& stderr, OrderSums& order_sums,
                      std::vector<double>& handed_on) {
        BatchReducer r(B, orders_, size_t(cells_), size_t(nc_));
        if (keep_ == BatchKeeping::hand_on) handed_on.resize(size_t(B) * map);
        for (int b = 0; b < B; ++b) {
            const double scale = inverse(rays_[size_t(b)]);
            double* x =
                keep_ == BatchKeeping::hand_on ? &handed_on[size_t(b) * map] : scaled.data();
            for (size_t i = 0; i < map; ++i) x[i] = sums[size_t(b) * map + i] * scale;
            r.add(x);
        }
        r.finish(mean, stderr, order_sums);
    };
    reduce(energy_, res.energy, res.energy_stderr, res.energy_sums, res.energy_batches);
    if (transmits_)
        reduce(transmitted_, res.transmitted, res.transmitted_stderr, res.transmitted_sums,
               res.transmitted_batches);
    complete_ledger(res, transmits_);
    return res;
}

void BatchTally::complete(TraceResult& res, bool transmits, bool hand_on) {
    const int B = res.batches, orders = res.orders;
    reduce_batches(res.energy_batches, B, orders, size_t(res.channels), res.energy,
                   res.energy_stderr, res.energy_sums);
    if (transmits)
        reduce_batches(res.transmitted_batches, B, orders, size_t(res.channels), res.transmitted,
                       res.transmitted_stderr, res.transmitted_sums);
    if (!hand_on)
        for (auto v : {&res.energy_batches, &res.transmitted_batches})
            std::vector<double>().swap(*v);
    complete_ledger(res, transmits);
}

} // namespace gonio
