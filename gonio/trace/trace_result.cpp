#include "gonio/trace/trace_result.h"

#include "core/batch_means.h"
#include "core/buffer_pool.h"
#include "core/check.h"

namespace gonio {

namespace {
// Which of the three sums orders from..to-1 are.
std::vector<double> OrderSums::*which(int from, int to, int orders) {
    if (from == 0 && to == 1) return &OrderSums::l1;
    if (from == 1 && to == orders) return &OrderSums::l2plus;
    GONIO_CHECK_MSG(from == 0 && to == orders, "order sums are kept for L1, L2+ and every order");
    return &OrderSums::linf;
}
} // namespace

const std::vector<double>& TraceResult::sum_batches(int from, int to, bool lower) const {
    GONIO_CHECK_MSG(!energy_sums.empty(), "a trace's order sums asked for after they were dropped");
    return (lower ? transmitted_sums : energy_sums).*which(from, to, orders);
}

std::vector<double> TraceResult::sum_stderr(int from, int to, bool lower) const {
    if (energy_sums.empty())
        return (lower ? transmitted_sums_stderr : sums_stderr).*which(from, to, orders);
    return batch_stderr(sum_batches(from, to, lower), batches);
}

void TraceResult::drop_order_sums() {
    if (energy_sums.empty()) return;
    for (auto [sums, errors] : {std::pair{&energy_sums, &sums_stderr},
                                std::pair{&transmitted_sums, &transmitted_sums_stderr}})
        for (auto field : {&OrderSums::l1, &OrderSums::l2plus, &OrderSums::linf})
            if (!(sums->*field).empty()) errors->*field = batch_stderr(sums->*field, batches);
    for (OrderSums* sums : {&energy_sums, &transmitted_sums})
        for (auto field : {&OrderSums::l1, &OrderSums::l2plus, &OrderSums::linf})
            give_back(std::move(sums->*field));
}

} // namespace gonio
