#pragma once
// Settings every subcommand derives from its options the same way.
#include "gonio/config/config.h"
#include "gonio/io/result_writer.h"
#include "gonio/pipeline/phase_times.h"
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
    cache_size_limit(); // a bad GONIO_CACHE_MAX fails now, not after a surface was made
    return SurfaceCache(cache_dir.empty() ? default_cache_directory() : cache_dir);
}

// A run's own phases: "config" is the loading of `cfg` since `start`, less its NDFs' (each case's
// "ndf" phase).
inline PhaseTimes run_phases(const Config& cfg, PhaseTimes::Clock::time_point start) {
    double ndf_seconds = 0;
    for (const CaseConfig& c : cfg.cases) ndf_seconds += c.ndf_seconds;
    PhaseTimes run;
    run.add("config",
            std::chrono::duration<double>(PhaseTimes::Clock::now() - start).count() - ndf_seconds);
    return run;
}

// Adds the wall time since `start` to the run's phases, writes them at the root and commits.
inline void finish_run(ResultWriter& writer, PhaseTimes run, PhaseTimes::Clock::time_point start) {
    run.add("wall", std::chrono::duration<double>(PhaseTimes::Clock::now() - start).count());
    writer.write_timings("", run.phases());
    writer.commit();
}

} // namespace gonio
