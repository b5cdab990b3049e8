#pragma once
// The tallies of a Monte Carlo beam kept per batch (core/batch_means.h): the simulator and the
// V-cavity estimator both split their rays into B independent batches of equal size, so that
// every reported mean comes with its standard error. Rays carry weight 1 while traced; a batch is
// divided by its ray count when it is reduced (batch_reducer.h).
//
// Blocks merge in a fixed order, batch after batch; a tally that streams keeps only the open
// batch's map and reduces it when the next batch opens (one map instead of B). An accuracy target
// adds rays to every batch in later rounds, and a batch shard hands its batches on: those keep
// every batch and reduce them, in the same order and so to the same bits, at finish().
#include "core/math.h"
#include "gonio/trace/batch_reducer.h"
#include "gonio/trace/trace_result.h"

#include <cstdint>
#include <memory>
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

// How a tally keeps its batches' maps.
enum class BatchKeeping {
    stream,  // the open batch only: batches close in order, each merged once
    memory,  // every batch, reduced at each finish() (rounds of an accuracy target)
    hand_on, // every batch, also in the result (a batch shard's, for combine_batch_shards)
};

class BatchTally {
  public:
    BatchTally(int batches, int orders, int cells, int channels, bool transmits);
    ~BatchTally(); // its maps kept for the next tally (core/buffer_pool.h)
    BatchTally(const BatchTally&) = delete;
    BatchTally& operator=(const BatchTally&) = delete;
    // Before the first merge (the default: memory).
    void keep(BatchKeeping k);
    // Adds a block of `rays` rays to batch b. Blocks must come in a fixed order (sums in floating
    // point depend on it): core/ordered_blocks.h gives that; a streaming tally takes each batch's
    // blocks together, batches in order.
    void merge(int b, const BlockOutput& o, long long rays);
    // The batches' means and standard errors, each batch divided by its own ray count. A
    // streaming tally is finished once.
    TraceResult finish();
    // The means, errors, order sums and the ledger's closing from the batches' own estimates
    // (energy_batches, transmitted_batches, ledger_batches of `res`, unaccounted excepted).
    // energy_batches and transmitted_batches are freed unless `hand_on`.
    static void complete(TraceResult& res, bool transmits, bool hand_on = false);

  private:
    void allocate();
    void close_open_batch();
    int batches_, orders_, cells_, nc_;
    bool transmits_;
    BatchKeeping keep_ = BatchKeeping::memory;
    bool allocated_ = false;
    int open_ = -1, reduced_ = 0;                  // streaming: the open batch, batches reduced
    std::vector<double> energy_, transmitted_;     // [batch][order][cell][channel] (or one batch)
    std::vector<double> reflected_, through_;      // [batch][order][channel]
    std::vector<double> absorbed_, capped_, lost_; // [batch][channel]
    std::vector<long long> rays_;
    long long segments_ = 0;
    std::unique_ptr<BatchReducer> energy_reducer_, transmitted_reducer_; // streaming
    struct OpenRows { // the rows (order * cells + cell) the open batch reached, per side
        std::vector<std::uint8_t> marked;
        std::vector<std::uint32_t> touched;
    };
    OpenRows open_rows_[2];
};

} // namespace gonio
