#pragma once
// Batches reduced as they close, in batch order, to what the error bars need: per order the sum
// of the batch estimates (their mean, in the bits batch_mean gives) and Welford's running sum of
// squared deviations (its standard error; Welford 1962, Technometrics 4(3), Eq. 1-2), and per
// batch the three order sums of OrderSums. A trace then holds one open batch instead of all B.
#include "gonio/trace/trace_result.h"

#include <cstddef>
#include <vector>

namespace gonio {

class BatchReducer {
  public:
    // B batches of `orders` orders of n values each ([order][n], n = cells * channels).
    BatchReducer(int batches, int orders, size_t n);
    // The next batch's estimates, [order][n]; batches come in order 0..B-1.
    void add(const double* batch);
    int added() const { return added_; }
    // After the B batches: the means and standard errors per order, and the order sums.
    void finish(std::vector<double>& mean, std::vector<double>& stderr, OrderSums& sums);

  private:
    int batches_, orders_, added_ = 0;
    size_t n_;
    std::vector<double> sum_, running_mean_, m2_; // [order][n]
    OrderSums sums_;
};

// The reduction of batches stored [batch][order][n] (an ensemble's surfaces, a shard's batches).
void reduce_batches(const std::vector<double>& batches, int B, int orders,
                    std::vector<double>& mean, std::vector<double>& stderr, OrderSums& sums);

} // namespace gonio
