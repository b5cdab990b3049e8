#include "gonio/trace/batch_reducer.h"

#include "core/check.h"

#include <cmath>

namespace gonio {

BatchReducer::BatchReducer(int batches, int orders, size_t n)
    : batches_(batches), orders_(orders), n_(n) {
    const size_t map = size_t(orders) * n, B = size_t(batches);
    sum_.assign(map, 0.0), running_mean_.assign(map, 0.0), m2_.assign(map, 0.0);
    for (auto* v : {&sums_.l1, &sums_.l2plus, &sums_.linf}) v->assign(B * n, 0.0);
}

void BatchReducer::add(const double* x) {
    GONIO_CHECK_MSG(added_ < batches_, "more batches than the reducer was made for");
    const double count = double(++added_);
    const size_t map = size_t(orders_) * n_;
    for (size_t i = 0; i < map; ++i) {
        sum_[i] += x[i];
        const double delta = x[i] - running_mean_[i];
        running_mean_[i] += delta / count;
        m2_[i] += delta * (x[i] - running_mean_[i]);
    }
    // The order sums from 0 in order, as sum_orders adds them.
    const size_t at = size_t(added_ - 1) * n_;
    double *l1 = &sums_.l1[at], *l2plus = &sums_.l2plus[at], *linf = &sums_.linf[at];
    for (int o = 0; o < orders_; ++o) {
        const double* xo = x + size_t(o) * n_;
        for (size_t i = 0; i < n_; ++i) {
            if (o == 0)
                l1[i] += xo[i];
            else
                l2plus[i] += xo[i];
            linf[i] += xo[i];
        }
    }
}

void BatchReducer::finish(std::vector<double>& mean, std::vector<double>& stderr, OrderSums& sums) {
    GONIO_CHECK_MSG(added_ == batches_, "a reduction of fewer batches than it was made for");
    const double B = double(batches_);
    mean = std::move(sum_);
    for (double& m : mean) m /= B;
    stderr = std::move(m2_);
    for (double& e : stderr) e = batches_ < 2 ? 0.0 : std::sqrt(e / (B * (B - 1)));
    sums = std::move(sums_);
}

void reduce_batches(const std::vector<double>& batches, int B, int orders,
                    std::vector<double>& mean, std::vector<double>& stderr, OrderSums& sums) {
    const size_t map = batches.size() / size_t(B);
    BatchReducer r(B, orders, map / size_t(orders));
    for (int b = 0; b < B; ++b) r.add(batches.data() + size_t(b) * map);
    r.finish(mean, stderr, sums);
}

} // namespace gonio
