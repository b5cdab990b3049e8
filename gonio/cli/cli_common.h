#pragma once
// Settings every subcommand derives from its options the same way.
#include "heightfield/surface_cache.h"

#include <memory>
#include <string>
#include <tbb/global_control.h>
#include <thread>

namespace gonio {

// Caps TBB at `threads` (> 0) for as long as the returned object lives; 0 leaves all cores.
inline std::unique_ptr<tbb::global_control> limit_threads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 threads);
}

// The worker count for FFTW: the option, or every core.
inline int worker_threads(int threads) {
    return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

// --no-cache disables the surface cache; --cache-dir overrides the default directory.
inline SurfaceCache surface_cache(bool no_cache, const std::string& cache_dir) {
    if (no_cache) return SurfaceCache(std::string());
    return SurfaceCache(cache_dir.empty() ? default_cache_directory() : cache_dir);
}

} // namespace gonio
