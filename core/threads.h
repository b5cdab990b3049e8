#pragma once
// How many threads gonio's work uses: TBB's workers (capped for as long as a limit lives) and
// FFTW's (a count). Results never depend on either.
#include <algorithm>
#include <memory>
#include <tbb/global_control.h>
#include <thread>

namespace gonio {

// Caps TBB at `threads` (> 0) for as long as the returned object lives; 0 leaves every core.
inline std::unique_ptr<tbb::global_control> limit_threads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 threads);
}

// The worker count of `threads` (0: every core).
inline int worker_threads(int threads) {
    return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

} // namespace gonio
