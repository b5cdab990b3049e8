#pragma once
// What the subcommands share: their registration (command.h), the options most of them take
// (declared once here), and the errors that end a command with a usage exit code.
#include "core/threads.h"
#include "gonio/cli/command.h"
#include "gonio/run/run.h"
#include "heightfield/surface_cache.h"

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

// A bad argument on the command line: "gonio: error: ..." and exit code 2, like a config error.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The options shared by the commands; each command asks for the ones it takes.
struct CommonOptions {
    std::string config;                 // kConfig: the TOML config file
    std::string output;                 // -o (each command declares it, in its own words)
    std::vector<std::string> overrides; // kSet: --set key=value
    bool overwrite = false;             // kOverwrite
    bool quiet = false;                 // kQuiet
    int threads = 0;                    // kThreads: 0 is every core
    bool no_cache = false;              // kCache: --no-cache and --cache-dir
    std::string cache_dir;
};
enum CommonOption : unsigned {
    kConfig = 1u << 0,
    kSet = 1u << 1,
    kOverwrite = 1u << 2,
    kQuiet = 1u << 3,
    kThreads = 1u << 4,
    kCache = 1u << 5,    // --no-cache and --cache-dir
    kCacheDir = 1u << 6, // --cache-dir alone
};
void add_common_options(CLI::App& app, CommonOptions& o, unsigned which);

// The surface cache the options name (--no-cache: none); a bad GONIO_CACHE_MAX fails now.
SurfaceCache surface_cache(const CommonOptions& o);
// $GONIO_CACHE_MAX in bytes (0: unset); a value that is no size is a UsageError.
long long checked_cache_limit();

// The library's run options from the command line's: threads, cache, SIGINT as the stop, the
// command line as provenance, and the wall time from `start` (the config read since then).
RunOptions run_options(const CommonOptions& o, const CliContext& context,
                       PhaseTimes::Clock::time_point start);

// <stem of the config>.<extension> in the working directory, unless `output` is given.
std::string output_or_default(const std::string& output, const std::string& config,
                              const std::string& extension);

// Refuses (UsageError, exit 2) an output that is a directory, or that exists without --overwrite.
void refuse_existing(const std::string& path, bool overwrite);

} // namespace gonio
