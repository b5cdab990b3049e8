#include "gonio/trace/batch_reducer.h"

#include "core/buffer_pool.h"
#include "core/check.h"

#include <algorithm>
#include <cmath>

namespace gonio {

BatchReducer::BatchReducer(int batches, int orders, size_t cells, size_t channels)
    : batches_(batches), orders_(orders), cells_(cells), nc_(channels) {
    const size_t rows = size_t(orders) * cells, map = rows * channels, n = cells * channels;
    sum_ = take_zeroed(map), m2_ = take_zeroed(map);
    seen_.assign(rows, 0);
    for (auto* v : {&sums_.l1, &sums_.l2plus, &sums_.linf}) *v = take_zeroed(size_t(batches) * n);
}

void BatchReducer::catch_up(size_t row, int batches) {
    const int missed = batches - seen_[row];
    if (missed <= 0) return;
    if (seen_[row] > 0) {
        // Chan, Golub & LeVeque 1983 (Am. Stat. 37(3)), Eq. 2.1: the pairwise merge of the row's
        // (n_a, mean = sum / n_a, M2) with `missed` batches of mean 0 and M2 0 (the sum stays).
        const double na = seen_[row], weight = missed / (na * (na + missed));
        const double* sum = &sum_[row * nc_];
        double* m2 = &m2_[row * nc_];
        for (size_t k = 0; k < nc_; ++k) m2[k] += sum[k] * sum[k] * weight;
    }
    seen_[row] = batches;
}

void BatchReducer::add_row(const double* x, size_t o, size_t cell) {
    const size_t row = o * cells_ + cell, at = row * nc_;
    const double* xr = x + at;
    bool touched = false;
    for (size_t k = 0; k < nc_; ++k) touched |= xr[k] != 0.0;
    if (!touched) return; // a zero batch for this row: merged when next touched
    const int b = added_ - 1;
    catch_up(row, b);
    // Welford 1962 (Technometrics 4(3)), Eq. 1-2, with the running mean read off the sum.
    const double before = b > 0 ? 1.0 / double(b) : 0.0, after = 1.0 / double(added_);
    double *sum = &sum_[at], *m2 = &m2_[at];
    for (size_t k = 0; k < nc_; ++k) {
        const double delta = xr[k] - sum[k] * before;
        sum[k] += xr[k];
        m2[k] += delta * (xr[k] - sum[k] * after);
    }
    seen_[row] = added_;
    // The order sums from order 0 up, as sum_orders adds them (zeros add nothing).
    const size_t n = cells_ * nc_, cb = size_t(b) * n + cell * nc_;
    double* part = o == 0 ? &sums_.l1[cb] : &sums_.l2plus[cb];
    double* linf = &sums_.linf[cb];
    for (size_t k = 0; k < nc_; ++k) part[k] += xr[k], linf[k] += xr[k];
}

void BatchReducer::add(const double* x) {
    GONIO_CHECK_MSG(added_ < batches_, "more batches than the reducer was made for");
    ++added_;
    for (size_t cell = 0; cell < cells_; ++cell)
        for (size_t o = 0; o < size_t(orders_); ++o) add_row(x, o, cell);
}

void BatchReducer::add(const double* x, std::vector<std::uint32_t>& rows) {
    GONIO_CHECK_MSG(added_ < batches_, "more batches than the reducer was made for");
    ++added_;
    // Cell by cell, orders ascending within each: the order of the whole batch's loop.
    const size_t cells = cells_, orders = size_t(orders_);
    auto key = [&](std::uint32_t r) { return (r % cells) * orders + r / cells; };
    std::sort(rows.begin(), rows.end(),
              [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
    for (std::uint32_t r : rows) add_row(x, r / cells, r % cells);
}

void BatchReducer::finish(std::vector<double>& mean, std::vector<double>& stderr, OrderSums& sums) {
    GONIO_CHECK_MSG(added_ == batches_, "a reduction of fewer batches than it was made for");
    for (size_t row = 0; row < seen_.size(); ++row) catch_up(row, batches_);
    const double B = double(batches_);
    mean = std::move(sum_);
    for (double& m : mean) m /= B;
    stderr = std::move(m2_);
    for (double& e : stderr) e = batches_ < 2 ? 0.0 : std::sqrt(e / (B * (B - 1)));
    sums = std::move(sums_);
}

void reduce_batches(const std::vector<double>& batches, int B, int orders, size_t channels,
                    std::vector<double>& mean, std::vector<double>& stderr, OrderSums& sums) {
    const size_t map = batches.size() / size_t(B);
    BatchReducer r(B, orders, map / size_t(orders) / channels, channels);
    for (int b = 0; b < B; ++b) r.add(batches.data() + size_t(b) * map);
    r.finish(mean, stderr, sums);
}

} // namespace gonio
