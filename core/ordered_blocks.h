#pragma once
// Monte Carlo work split into blocks with their own random streams: blocks run in parallel a
// batch at a time, then are merged in block order, so that the sums do not depend on the threads;
// the batch's outputs are reused, which keeps memory flat.
#include "core/parallel.h"

#include <algorithm>
#include <tbb/task_arena.h>
#include <vector>

namespace gonio {

// work(b, out) fills `out` for block b (any thread); merge(out) is called in block order.
template <class Output, class Work, class Merge>
void run_blocks_in_order(long long blocks, const Work& work, const Merge& merge) {
    const long long batch = std::max(256, 16 * tbb::this_task_arena::max_concurrency());
    std::vector<Output> out(size_t(std::min(blocks, batch)));
    for (long long b0 = 0; b0 < blocks; b0 += batch) {
        const long long b1 = std::min(blocks, b0 + batch);
        parallel_for(b0, b1, [&](long long b) { work(b, out[size_t(b - b0)]); });
        for (long long b = b0; b < b1; ++b) merge(out[size_t(b - b0)]);
    }
}

} // namespace gonio
