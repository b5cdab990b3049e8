#pragma once
// The gonio subcommands; each returns the process exit code.
#include "gonio/render/renderer.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

struct ModelOptions {
    std::string config;
    std::string output; // default: <config stem>.h5 in the working directory
    std::vector<std::string> overrides;
    bool overwrite = false;
    bool quiet = false;
    int threads = 0; // 0: all cores
    std::string command_line;
};
// `gonio model`: Model L1 of every case and incidence, written to HDF5.
int run_model_command(const ModelOptions& options);

struct SurfaceOptions {
    std::string config;
    std::string output; // default: <config stem>_<case>.exr
    std::vector<std::string> overrides;
    bool overwrite = false;
    bool quiet = false;
    bool no_cache = false;
    std::string cache_dir; // default: default_cache_directory()
    int threads = 0;
};
// `gonio surface`: the microsurface of every case (cached), its EXR height map and NDF comparison.
int run_surface_command(const SurfaceOptions& options);

struct RunOptions {
    std::string config;
    std::string output; // default: <config stem>.h5
    std::vector<std::string> overrides;
    bool overwrite = false;
    bool quiet = false;
    bool no_cache = false;
    std::string cache_dir;
    int threads = 0;
    std::string command_line;
    std::string shard;   // "i/N": trace that share of the work units into a part file
    bool resume = false; // continue from OUT.checkpoint
};
// `gonio run`: trace every case and incidence on the explicit surface; write HDF5.
int run_run_command(const RunOptions& options);

struct NdfOptions {
    std::string config;
    std::string csv; // optional: the curves at 0.5 degree steps
    std::vector<std::string> overrides;
    int threads = 0;
};
// `gonio ndf`: each case's D and Lambda along phi = 0 and pi/2, and its Model L1 albedo.
int run_ndf_command(const NdfOptions& options);

// `gonio compare FILE`: the Model-vs-simulated table of a result file.
int run_compare_command(const std::string& path);

// `gonio keys [--markdown]`: every config key, from the components' declarations.
int run_keys_command(bool markdown);

struct ExportOptions;
// `gonio export FILE --format F -o OUT`: the simulated BSDF in a format other tools read
// (gonio/export/export.h); exit 3 when the format cannot hold the case.
int run_export_command(const ExportOptions& options);

// `gonio render FILE -o OUT.png`: the case's tabulated BSDF on an object (gonio/render).
struct RenderOptions {
    std::string input, output, case_name;
    std::string compare; // "", "l1" or "model"
    std::string object = "sphere";
    std::string env = "sky"; // uniform, sky or an EXR path
    RenderSettings settings;
    bool overwrite = false, quiet = false;
    int threads = 0;
};
// A bad argument of `gonio render` (exit 2, like a config error).
struct RenderArgumentError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
int run_render_command(const RenderOptions& options);

// `gonio merge PART... -o OUT`: the parts of a sharded run, checked and put together.
int run_merge_command(const std::vector<std::string>& parts, const std::string& output,
                      bool overwrite, bool quiet, int threads);

// `gonio cache list|clear [--cache-dir DIR]`: the shared surface cache.
int run_cache_command(const std::string& action, const std::string& directory);

// `gonio info FILE [--json]`.
int run_info_command(const std::string& path, bool as_json);

} // namespace gonio
