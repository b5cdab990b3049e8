#include "gonio/cli/cli_common.h"

#include "gonio/cli/stop_signal.h"

#include <filesystem>

namespace gonio {

void add_common_options(CLI::App& app, CommonOptions& o, unsigned which) {
    if (which & kConfig) app.add_option("config", o.config, "TOML config file")->required();
    if (which & kSet)
        app.add_option("--set", o.overrides,
                       "Override a config key, e.g. --set ndf.alpha=0.3 or "
                       "--set case.1.beam.theta_i=[0,60] (repeatable)");
    if (which & kOverwrite)
        app.add_flag("--overwrite", o.overwrite, "Replace existing output files");
    if (which & kQuiet) app.add_flag("-q,--quiet", o.quiet, "No progress and no table");
    if (which & kThreads)
        app.add_option("--threads", o.threads, "Worker threads (default: all cores)")
            ->check(CLI::Range(0, 1024));
    if (which & kCache)
        app.add_flag("--no-cache", o.no_cache, "Neither read nor write the surface cache");
    if (which & (kCache | kCacheDir))
        app.add_option("--cache-dir", o.cache_dir,
                       "Surface cache directory (default: $GONIO_CACHE_DIR, else "
                       "~/.cache/gonio/surfaces)");
}

long long checked_cache_limit() {
    try {
        return cache_size_limit();
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
}

SurfaceCache surface_cache(const CommonOptions& o) {
    if (o.no_cache) return SurfaceCache(std::string());
    checked_cache_limit(); // a bad GONIO_CACHE_MAX fails now, not after a surface was made
    return SurfaceCache(o.cache_dir.empty() ? default_cache_directory() : o.cache_dir);
}

RunOptions run_options(const CommonOptions& c, const CliContext& context,
                       PhaseTimes::Clock::time_point start) {
    RunOptions o;
    o.threads = c.threads;
    o.cache = surface_cache(c);
    o.stop_requested = [] { return stop_requested(); };
    o.command_line = context.command_line;
    o.started = start;
    o.config_seconds = std::chrono::duration<double>(PhaseTimes::Clock::now() - start).count();
    return o;
}

std::string output_or_default(const std::string& output, const std::string& config,
                              const std::string& extension) {
    return output.empty() ? std::filesystem::path(config).stem().string() + extension : output;
}

void refuse_existing(const std::string& path, bool overwrite) {
    if (std::filesystem::is_directory(path))
        throw UsageError(path + ": is a directory; the output is a file");
    if (!overwrite && std::filesystem::exists(path))
        throw UsageError(path + ": exists; pass --overwrite to replace it");
}

} // namespace gonio
