#pragma once
// Batches reduced as they close, in batch order, to what the error bars need: per order the sum
// of the batch estimates (their mean, in the bits batch_mean gives) and Welford's running sum of
// squared deviations (its standard error), and per batch the three order sums of OrderSums. A
// trace then holds one open batch instead of all B.
//
// Most rows of a batch (an order's cell, its channels) receive no ray: a row is touched in a
// batch when one of its values is non-zero, and only touched rows are worked on. The zero batches
// a row missed are merged in closed form when it is next touched or at finish(), so a sparse
// batch (the touched cells only) and the same batch given whole reduce to the same bits.
#include "gonio/trace/trace_result.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gonio {

class BatchReducer {
  public:
    // B batches of `orders` orders of `cells` cells of `channels` values ([order][cell][channel]).
    BatchReducer(int batches, int orders, size_t cells, size_t channels);
    // The next batch's estimates, [order][cell][channel]; batches come in order 0..B-1.
    void add(const double* batch);
    // The same, when only `rows` (order * cells + cell, each once, any order) may hold non-zero
    // values. They are sorted here.
    void add(const double* batch, std::vector<std::uint32_t>& rows);
    int added() const { return added_; }
    // After the B batches: the means and standard errors per order, and the order sums.
    void finish(std::vector<double>& mean, std::vector<double>& stderr, OrderSums& sums);

  private:
    void add_row(const double* batch, size_t order, size_t cell);
    void catch_up(size_t row, int batches); // merges the zero batches `row` missed
    int batches_, orders_, added_ = 0;
    size_t cells_, nc_;
    std::vector<double> sum_, m2_; // [order][cell][channel]
    std::vector<int> seen_;        // [order][cell]: batches merged into the row
    OrderSums sums_;
};

// The reduction of batches stored [batch][order][cell][channel] (an ensemble's surfaces, a
// shard's batches): the bits a streaming reduction of the same batches gives.
void reduce_batches(const std::vector<double>& batches, int B, int orders, size_t channels,
                    std::vector<double>& mean, std::vector<double>& stderr, OrderSums& sums);

} // namespace gonio
