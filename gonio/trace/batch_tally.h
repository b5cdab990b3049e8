#pragma once
// The tallies of a Monte Carlo beam kept per batch (core/batch_means.h): the simulator and the
// V-cavity estimator both split their rays into B independent batches of equal size, so that
// every reported mean comes with its standard error. Rays carry weight 1 while traced; finish()
// divides each batch by its ray count, so batches may grow (a target-accuracy run adds rounds).
#include "core/math.h"
#include "gonio/trace/trace_result.h"

#include <vector>

namespace gonio {

// What one block of rays produced: its exits, in ray order, and its ledger sums.
struct BlockOutput {
    std::vector<int> bin;       // order * cells + cell, + orders * cells when it left downwards
    std::vector<Vec3> exit;     // exit directions, when the block bins them after tracing
    std::vector<double> weight; // channels per exit
    std::vector<double> absorbed, capped, lost;
    long long segments = 0;
    void clear(int channels);
};

class BatchTally {
  public:
    BatchTally(int batches, int orders, int cells, int channels, bool transmits);
    // Adds a block of `rays` rays to batch b. Blocks must come in a fixed order (sums in floating
    // point depend on it): core/ordered_blocks.h gives that.
    void merge(int b, const BlockOutput& o, long long rays);
    // The batches' means and standard errors, each batch divided by its own ray count.
    TraceResult finish() const;
    // The means, errors and the ledger's closing from the batches' own estimates (energy_batches,
    // transmitted_batches, ledger_batches of `res`, unaccounted excepted): what finish() does
    // after dividing the sums.
    static void complete(TraceResult& res, bool transmits);

  private:
    int batches_, orders_, cells_, nc_;
    bool transmits_;
    std::vector<double> energy_, transmitted_;     // [batch][order][cell][channel]
    std::vector<double> reflected_, through_;      // [batch][order][channel]
    std::vector<double> absorbed_, capped_, lost_; // [batch][channel]
    std::vector<long long> rays_;
    long long segments_ = 0;
};

} // namespace gonio
