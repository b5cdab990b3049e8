#pragma once
// A gonio run as a library call. A config's work is cut into units (unit.h); an executor computes
// some of them (trace_case: traces and models) and assembles the result from all of them
// (CaseAssembler). The executors differ only in where units are computed and how they travel:
//   run_local     every unit in this process; with a checkpoint, each finished unit is kept in a
//                 unit file beside the output and a later call resumes from it;
//   run_shard     the units of one shard, into a part file;
//   merge_parts   the part files of every shard, put together;
//   run_mpi       under mpirun, each rank computes its units and rank 0 assembles;
//   run_models    the models alone (gonio model), no surface traced.
// Same config and seed: the same result, bit for bit, whichever executor, threads or ranks (every
// call computes in one floating-point mode, core/float_mode.h, and restores the caller's).
//
//     Config cfg = load_config("configs/quickstart.toml");
//     RunResult r = run_local(cfg, {});
//     write_result_file(r, "quickstart.h5", /*overwrite=*/true);
#include "core/threads.h"
#include "gonio/config/config.h"
#include "gonio/run/case_assembler.h"
#include "gonio/run/phase_times.h"
#include "gonio/run/run_context.h"
#include "gonio/run/unit.h"

#include <optional>
#include <string>
#include <vector>

namespace gonio {

struct RunOptions {
    int threads = 0; // worker threads; 0: every core (the caller caps TBB: limit_threads)
    SurfaceCache cache{std::string()}; // disabled unless given
    RunObserver observer;
    std::function<bool()> stop_requested; // checked between units: throws Interrupted
    std::string command_line;             // provenance, stored in the file
    // When the caller began (the file's wall time counts from it), and how long it took to load
    // the config (the phase "config", less the distributions' own time, each case's "ndf").
    PhaseTimes::Clock::time_point started = PhaseTimes::Clock::now();
    double config_seconds = 0;
};

// How the run was spread: provenance for the file (root attributes), not data.
struct Execution {
    int ranks = 1, threads_per_rank = 1, merged_parts = 0;
    double memory_estimate_bytes = 0; // memory_estimate.h, before the run (0: not estimated)
};

struct RunResult {
    Config config;
    bool simulated = true;         // traced (run), or models only (model)
    std::vector<CaseResult> cases; // in config order
    PhaseTimes phases;             // the run's own: config, checkpoint
    Execution execution;
    std::string command_line;
    PhaseTimes::Clock::time_point started;
};

// A checkpoint: the unit file that keeps every finished unit of an in-process run.
struct Checkpoint {
    std::string path;    // empty: none
    bool resume = false; // continue from it (it must exist and come from the same run)
};

// Every unit in this process. With a checkpoint, each unit is added to it as it finishes; on
// success it is left for the caller to remove once the result is safely written; an interrupt
// leaves it (to resume from), any other failure removes a checkpoint this call created.
RunResult run_local(const Config& cfg, const RunOptions& options,
                    const Checkpoint& checkpoint = {});

// The models of every case and incidence (no trace; a surface only for a model fitted to one).
RunResult run_models(const Config& cfg, const RunOptions& options);

// The units of `shard` into the part file `part` (written under a temporary name and renamed
// when complete); returns how many. A single-incidence job shards its batches instead.
long long run_shard(const Config& cfg, const RunOptions& options, const Shard& shard,
                    const std::string& part);

// The part files of every shard of one run: checked (same run, no unit missing or twice) and
// assembled. The config comes from the parts.
RunResult merge_parts(const std::vector<std::string>& parts, const RunOptions& options);

// Under mpirun: every rank computes its share; rank 0 gets the result, the others nothing.
std::optional<RunResult> run_mpi(const Config& cfg, const RunOptions& options);

// The result file (gonio/io/result_writer.h), written under a temporary name and renamed.
class ResultWriter;
void write_result(const RunResult& result, ResultWriter& writer);
void write_result_file(const RunResult& result, const std::string& path, bool overwrite);

} // namespace gonio
