// `gonio run CONFIG`: every case and incidence traced on the explicit surface, the models on the
// same cells, written to HDF5; in this process (with a checkpoint for --resume), as one shard of
// a job array (--shard), or across the ranks of mpirun. The work itself is the library's
// (gonio/run/run.h); this parses, calls and prints.
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/cli/progress.h"
#include "gonio/cli/run_table.h"
#include "gonio/cli/stop_signal.h"
#include "gonio/io/result_writer.h"
#include "gonio/run/memory_estimate.h"
#include "gonio/run/mpi_job.h"
#include "gonio/run/run.h"

#include <cstdio>
#include <filesystem>

namespace gonio {

namespace {
struct RunArgs {
    CommonOptions common;
    std::string shard;   // "i/N" or "slurm"
    bool resume = false; // continue from OUT.checkpoint
};

// Every unit here, kept in OUT.checkpoint as it finishes; the checkpoint goes once the result is
// written.
int run_here(const Config& cfg, RunOptions o, const RunArgs& a, const std::string& output) {
    const std::string checkpoint = output + ".checkpoint";
    if (a.resume && !std::filesystem::exists(checkpoint))
        throw UsageError(checkpoint + ": no checkpoint to resume (run without --resume)");
    if (!a.resume && std::filesystem::exists(checkpoint) && !a.common.overwrite)
        throw UsageError(checkpoint + ": an interrupted run's checkpoint; pass --resume to "
                                      "continue it or --overwrite to start again");
    refuse_existing(output, a.common.overwrite);
    ResultWriter writer(output, true); // an unwritable output fails here, before any work
    if (!a.common.quiet) {
        const MemoryEstimate m = estimate_memory(cfg, true);
        std::printf("memory: about %.0f MB at the peak (most of it %s)\n", m.bytes / 1e6,
                    m.largest.c_str());
    }
    RunTable table(UnitLayout(cfg).total(), a.common.quiet, checkpoint);
    o.observer = table.observer();
    RunResult result;
    try {
        result = run_local(cfg, o, {checkpoint, a.resume});
    } catch (const Interrupted&) {
        table.finish();
        std::fprintf(stderr,
                     "gonio: interrupted; the finished incidences are in %s: `gonio run ... "
                     "--resume` continues the run\n",
                     checkpoint.c_str());
        return 130;
    }
    table.finish();
    try {
        write_result(result, writer);
    } catch (...) { // nothing left behind: not the checkpoint this run made either
        std::error_code ec;
        if (!a.resume) std::filesystem::remove(checkpoint, ec);
        throw;
    }
    std::filesystem::remove(checkpoint);
    if (!a.common.quiet) std::printf("wrote %s\n", output.c_str());
    return 0;
}

// One shard's units into a part file, for gonio merge.
int run_as_shard(const Config& cfg, RunOptions o, const RunArgs& a, const Shard& shard,
                 const std::string& output) {
    if (a.resume)
        throw UsageError("--resume with --shard: a shard keeps no checkpoint; run the shard again");
    refuse_existing(output, a.common.overwrite);
    const long long total = UnitLayout(cfg).total();
    Progress progress(total / shard.count + 1, a.common.quiet);
    long long done = 0;
    o.observer.started = [&](const std::string& label) { progress.update(done, label); };
    o.observer.unit_done = [&](const UnitId&) { ++done; };
    long long written = 0;
    try {
        written = run_shard(cfg, o, shard, output);
    } catch (const Interrupted&) {
        progress.finish();
        std::fprintf(stderr, "gonio: interrupted; shard %s wrote nothing (run it again)\n",
                     shard.text().c_str());
        return 130;
    }
    progress.finish();
    if (!a.common.quiet)
        std::printf(
            "wrote %s: shard %s, %lld of %lld units (gonio merge puts the parts together)\n",
            output.c_str(), shard.text().c_str(), written, total);
    return 0;
}

// Under mpirun: rank 0 writes; a rank that fails ends the job.
int run_on_ranks(const Config& cfg, RunOptions o, const RunArgs& a, const CliContext& context,
                 const std::string& output) {
    try {
        if (a.common.no_cache)
            throw UsageError("--no-cache: the ranks of an MPI job share their surfaces through "
                             "the cache");
        if (a.resume || !a.shard.empty())
            throw UsageError("--resume and --shard are for runs without mpirun");
        const bool root = context.rank == 0;
        if (root) refuse_existing(output, a.common.overwrite);
        RunTable table(UnitLayout(cfg).total(), a.common.quiet || !root);
        o.observer = table.observer();
        const std::optional<RunResult> result = run_mpi(cfg, o);
        table.finish();
        if (!result) return 0;
        write_result_file(*result, output, a.common.overwrite);
        if (!a.common.quiet) std::printf("wrote %s\n", output.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gonio: error (rank %d of %d): %s\n", context.rank, context.ranks,
                     e.what());
        mpi_abort(1);
    }
}

Shard shard_of(const std::string& text) {
    if (text.empty()) return {};
    try {
        if (text != "slurm") return parse_shard(text);
        const Shard s = shard_from_environment();
        if (!s.active())
            throw UsageError("--shard slurm: SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT are "
                             "not set (not a task of a Slurm job array)");
        return s;
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
}

int run(const RunArgs& a, const CliContext& context) {
    const auto start = PhaseTimes::Clock::now();
    const Config cfg = load_config(a.common.config, a.common.overrides); // throws ConfigError
    cfg.require_beam("gonio run");
    const auto limit = limit_threads(a.common.threads);
    const std::string output = output_or_default(a.common.output, a.common.config, ".h5");
    install_stop_handlers();
    const RunOptions o = run_options(a.common, context, start);
    if (context.ranks > 1) return run_on_ranks(cfg, o, a, context, output);
    const Shard shard = shard_of(a.shard);
    if (shard.active()) return run_as_shard(cfg, o, a, shard, output);
    return run_here(cfg, o, a, output);
}

std::function<int()> setup(CLI::App& app, const CliContext& context) {
    auto a = std::make_shared<RunArgs>();
    add_common_options(app, a->common, kConfig | kSet | kOverwrite | kQuiet | kThreads | kCache);
    app.add_option("-o,--output", a->common.output, "HDF5 result file (default: <config>.h5)");
    app.add_option("--shard", a->shard,
                   "i/N: trace only shard i of N into a part file for gonio merge; 'slurm': i and "
                   "N from SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT");
    app.add_flag("--resume", a->resume, "Continue an interrupted run from OUT.checkpoint");
    return [a, context] {
        RunArgs args = *a;
        args.common.quiet = args.common.quiet || context.rank != 0;
        return run(args, context);
    };
}
} // namespace

const Command& run_command() {
    static const Command c{
        "run", "Trace every case and incidence on the explicit microsurface; compare with Model L1",
        setup};
    return c;
}

} // namespace gonio
