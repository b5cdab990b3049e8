#pragma once
// The schedule every Monte Carlo beam of gonio follows: B batches of `per_batch` rays per round,
// each batch cut into blocks of settings.block rays with their own random streams (keyed by the
// block's number, which does not depend on the threads), run in parallel and merged in block
// order. One round, unless the settings carry an accuracy target: then rounds are added, as many
// as the current error predicts are needed, until the target is met or its budget is spent.
#include "core/ordered_blocks.h"
#include "gonio/trace/batch_tally.h"
#include "gonio/trace/gonioreflectometer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace gonio {

// trace(id, first, last, out): rays first..last-1 (of per_batch) of one batch's round, into out.
template <class Trace>
TraceResult run_batched(const TraceSettings& st, long long per_batch, BatchTally& tally,
                        const BeckersSensor& sensor, const Trace& trace) {
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    const long long B = std::max(1, st.batches);
    const long long per_block = std::max(1, st.block);
    const long long batch_blocks = (per_batch + per_block - 1) / per_block;
    const long long round_blocks = B * batch_blocks, round_rays = B * per_batch;
    const AccuracyTarget& target = st.target;
    const int shards = std::max(1, st.batch_shard_count), shard = st.batch_shard_index;
    const long long max_rounds =
        target.active() ? std::max(1LL, target.max_rays / std::max(1LL, round_rays)) : 1;
    // Without a target every batch is complete when its last block merges (blocks run batch
    // after batch): the tally keeps the open batch alone. A batch shard hands its batches on.
    tally.keep(shards > 1        ? BatchKeeping::hand_on
               : target.active() ? BatchKeeping::memory
                                 : BatchKeeping::stream);
    long long done = 0, next = 1;
    for (;;) {
        const long long first_block = done * round_blocks;
        long long merged = first_block;
        run_blocks_in_order<BlockOutput>(
            (next - done) * round_blocks,
            [&](long long b, BlockOutput& o) {
                const long long id = first_block + b, k = id % batch_blocks;
                if ((id / batch_blocks) % B % shards != shard) return; // another shard's batch
                trace(id, k * per_block, std::min(per_batch, (k + 1) * per_block), o);
            },
            [&](const BlockOutput& o) {
                const long long id = merged++, k = id % batch_blocks;
                const long long rays = std::min(per_batch, (k + 1) * per_block) - k * per_block;
                const int batch = int((id / batch_blocks) % B);
                if (batch % shards == shard) tally.merge(batch, o, rays);
            });
        done = next;
        TraceResult res = tally.finish();
        res.rounds = done;
        const double seconds = elapsed();
        if (!target.active()) {
            res.seconds = seconds;
            return res;
        }
        const double error = relative_error_of(res, target, sensor);
        res.achieved_error = error;
        res.seconds = seconds;
        if (error <= target.relative_error) {
            res.stop = StopReason::target;
            return res;
        }
        if (done >= max_rounds) {
            res.stop = StopReason::max_rays;
            return res;
        }
        const double per_round = seconds / double(done);
        const long long affordable =
            (long long)std::floor((target.max_seconds - seconds) / per_round);
        if (affordable < 1) {
            res.stop = StopReason::max_seconds;
            return res;
        }
        // The error falls as 1/sqrt(rays): aim a little past the predicted need, since the error
        // estimate is itself uncertain by about 1/sqrt(2 (B - 1)).
        const double ratio = error / target.relative_error;
        const long long need = (long long)std::ceil(double(done) * ratio * ratio * 1.05);
        next = std::min({std::max(need, done + 1), max_rounds, done + affordable});
    }
}

} // namespace gonio
