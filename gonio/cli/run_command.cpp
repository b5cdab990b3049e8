#include "gonio/cli/cli_common.h"
#include "gonio/cli/commands.h"
#include "gonio/cli/progress.h"
#include "gonio/config/config.h"
#include "gonio/distributed/mpi_job.h"
#include "gonio/distributed/stop_signal.h"
#include "gonio/distributed/unit_file.h"
#include "gonio/io/result_writer.h"
#include "gonio/pipeline/simulate_case.h"
#include "gonio/trace/gonioreflectometer.h"
#include "gonio_version.h"
#include "heightfield/surface_source.h"

#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <unistd.h>

namespace gonio {

namespace {
// One row per channel of a finished incidence: simulated L1 with its error, the first model of
// single scattering beside it (every model is in the file), L2+, the transmitted and lost parts.
void print_incidence(const CaseConfig& c, const IncidenceReport& r, int shown) {
    const TraceResult& t = *r.trace;
    const SimulationResult& sim = *r.simulation;
    const size_t ti = r.theta_index, pi = r.phi_index;
    for (size_t k = 0; k < size_t(c.channels()); ++k) {
        const Estimate& l1 = sim.reflected.first_albedo;
        std::printf("%-20s %7.2f %7.2f %10.6f %8.1e", c.name.c_str(), r.theta_deg, r.phi_deg,
                    l1.mean.at({ti, pi, k}), l1.error.at({ti, pi, k}));
        if (shown >= 0) {
            const Comparison& cmp = (*r.comparisons)[size_t(shown)];
            std::printf(" %10.6f %+10.4f %+7.1f", cmp.model_albedo[k], cmp.relative_difference[k],
                        cmp.sigmas[k]);
        } else {
            std::printf(" %10s %10s %7s", "-", "-", "-");
        }
        std::printf(" %10.6f", sim.reflected.higher_albedo.mean.at({ti, pi, k}));
        if (c.material.transmits)
            std::printf(" %10.6f", sim.transmitted.all_albedo.mean.at({ti, pi, k}));
        else
            std::printf(" %10s", "-");
        std::printf(" %9.2e", sim.lost.mean.at({ti, pi, k}));
        if (c.trace.target.active())
            std::printf("  %s: %.2e with %lld rays", t.stop.c_str(), t.achieved_error, t.rays);
        std::printf("\n");
    }
}

UnitFileHeader unit_header(const Config& cfg, const std::string& command_line) {
    UnitFileHeader h;
    h.version = kVersion;
    h.git_hash = kGitHash;
    h.effective_toml = cfg.effective_toml;
    h.config_path = cfg.path;
    h.config_toml = cfg.text;
    for (const auto& ov : cfg.overrides) h.overrides += ov + "\n";
    h.command_line = command_line;
    h.seed = (long long)cfg.seed;
    for (const auto& c : cfg.cases)
        h.units_total += (long long)(c.theta_i_deg.size() * c.phi_i_deg.size());
    return h;
}

// The first unit number of each case: units run over cases, then theta_i, then phi_i.
std::vector<long long> first_units(const Config& cfg) {
    std::vector<long long> first;
    long long u = 0;
    for (const auto& c : cfg.cases) {
        first.push_back(u);
        u += (long long)(c.theta_i_deg.size() * c.phi_i_deg.size());
    }
    return first;
}

int assemble_and_write(
    const Config& cfg, const RunOptions& o, const std::string& output,
    const std::vector<std::map<IncidenceKey, UnitTraces>>& done,
    const std::function<void(size_t ci, size_t ti, size_t pi, const UnitTraces&)>& traced,
    PhaseTimes run, PhaseTimes::Clock::time_point start, int ranks, int merged_parts) {
    auto t = PhaseTimes::Clock::now();
    ResultWriter writer(output, o.overwrite); // an existing or unwritable output fails here
    writer.write_run(cfg, o.command_line);
    writer.write_execution(ranks, worker_threads(o.threads), merged_parts);
    t = run.add_since("writing", t);

    long long total = 0, finished = 0;
    for (const auto& c : cfg.cases) total += c.theta_i_deg.size() * c.phi_i_deg.size();
    if (!o.quiet)
        std::printf("%-20s %7s %7s %10s %8s %10s %10s %7s %10s %10s %9s\n", "case", "theta_i",
                    "phi_i", "L1", "+-", "model", "rel_diff", "sigmas", "L2+", "T", "lost");
    Progress progress(total, o.quiet);
    CaseRunSettings settings;
    settings.seed = cfg.seed;
    settings.threads = worker_threads(o.threads);
    settings.cache = surface_cache(o.no_cache, o.cache_dir);
    for (size_t ci = 0; ci < cfg.cases.size(); ++ci) {
        const CaseConfig& c = cfg.cases[ci];
        // The terminal shows the first model of single scattering next to L1.
        int shown = -1;
        for (size_t m = 0; m < c.model.models.size() && shown < 0; ++m)
            if (c.model.models[m].compared_with == "l1") shown = int(m);
        CaseObserver observer;
        observer.started = [&](const std::string& label) { progress.update(finished, label); };
        observer.finished = [&](const IncidenceReport& r) {
            ++finished;
            if (o.quiet) return;
            progress.finish();
            print_incidence(c, r, shown);
        };
        observer.warn = [](const std::string& w) {
            std::fprintf(stderr, "gonio: warning: %s\n", w.c_str());
        };
        UnitPlan plan;
        plan.done = &done[ci];
        if (traced)
            plan.traced = [&, ci](size_t ti, size_t pi, const UnitTraces& u) {
                traced(ci, ti, pi, u);
            };
        plan.stop_requested = [] { return stop_requested(); };
        settings.case_index = ci;
        settings.plan = &plan;
        const CaseResult result = simulate_case(c, settings, observer);
        progress.finish();
        t = PhaseTimes::Clock::now();
        writer.write_simulation_case(c, *result.sensor, c.ndf->describe(), result.simulation,
                                     result.models);
        PhaseTimes phases = result.phases;
        phases.add_since("writing", t);
        writer.write_timings(c.name, phases.phases());
        run.merge(phases);
        t = PhaseTimes::Clock::now();
    }
    run.add_since("writing", t);
    finish_run(writer, run, start);
    if (!o.quiet) std::printf("wrote %s\n", output.c_str());
    return 0;
}

// A shard: trace the units it owns, write them to the part file.
int run_shard(const Config& cfg, const RunOptions& o, const Shard& shard,
              const std::string& output) {
    if (!o.overwrite && std::filesystem::exists(output))
        throw std::runtime_error(output + ": exists; pass --overwrite to replace it");
    UnitFileHeader header = unit_header(cfg, o.command_line);
    header.shard = shard.text();
    // A single-incidence job has one unit: its shards share out the batches instead.
    header.by_batches = header.units_total == 1;
    Config local = cfg;
    if (header.by_batches) {
        CaseConfig& c = local.cases[0];
        if (c.trace.target.active() || c.surface.realisations > 1)
            throw std::runtime_error(
                "--shard " + shard.text() +
                ": a single-incidence job shards by batches, which an accuracy "
                "target or a surface ensemble does not allow");
        if (shard.count > c.trace.batches)
            throw std::runtime_error("--shard " + shard.text() + ": more shards than the " +
                                     std::to_string(c.trace.batches) + " batches (trace.batches)");
        c.trace.batch_shard_index = shard.index;
        c.trace.batch_shard_count = shard.count;
    }
    const std::string tmp = output + ".tmp-" + std::to_string(::getpid());
    long long written = 0;
    try {
        UnitFileWriter part(tmp, header, false);
        const std::vector<long long> first = first_units(cfg);
        Progress progress(header.units_total / shard.count + 1, o.quiet);
        CaseRunSettings settings;
        settings.seed = cfg.seed;
        settings.threads = worker_threads(o.threads);
        settings.cache = surface_cache(o.no_cache, o.cache_dir);
        for (size_t ci = 0; ci < local.cases.size(); ++ci) {
            const CaseConfig& c = local.cases[ci];
            const size_t np = c.phi_i_deg.size();
            UnitPlan plan;
            plan.trace_only = true;
            plan.owned = [&](size_t ti, size_t pi) {
                return header.by_batches || shard.owns(first[ci] + (long long)(ti * np + pi));
            };
            plan.traced = [&](size_t ti, size_t pi, const UnitTraces& u) {
                part.add({first[ci] + (long long)(ti * np + pi), ci, ti, pi, u});
                progress.update(++written, c.name);
            };
            plan.stop_requested = [] { return stop_requested(); };
            settings.case_index = ci;
            settings.plan = &plan;
            simulate_case(c, settings);
        }
        progress.finish();
        part.close();
    } catch (...) {
        std::remove(tmp.c_str());
        throw;
    }
    std::error_code ec;
    std::filesystem::rename(tmp, output, ec);
    if (ec)
        throw std::runtime_error("cannot rename " + tmp + " to " + output + ": " + ec.message());
    if (!o.quiet)
        std::printf(
            "wrote %s: shard %s, %lld of %lld units (gonio merge puts the parts together)\n",
            output.c_str(), shard.text().c_str(), written, header.units_total);
    return 0;
}
// Under mpirun: every surface made once (the k-th by rank k mod K, shared through the cache),
// each rank traces the units u with u mod K = its rank and sends them to rank 0, which writes
// the result as one process would. A rank that fails ends the job.
int run_mpi(const Config& cfg, const RunOptions& o, const std::string& output, PhaseTimes run,
            PhaseTimes::Clock::time_point start) {
    const MpiJob& job = mpi_job();
    try {
        if (o.no_cache)
            throw std::runtime_error("--no-cache: the ranks of an MPI job share their surfaces "
                                     "through the cache");
        if (o.resume || !o.shard.empty())
            throw std::runtime_error("--resume and --shard are for runs without mpirun");
        if (job.rank == 0 && !o.overwrite && std::filesystem::exists(output))
            throw std::runtime_error(output + ": exists; pass --overwrite to replace it");
        CaseRunSettings settings;
        settings.seed = cfg.seed;
        settings.threads = worker_threads(o.threads);
        settings.cache = surface_cache(false, o.cache_dir);
        long long k = 0;
        for (const CaseConfig& c : cfg.cases)
            for (int r = 0; r < c.surface.realisations; ++r)
                if (k++ % job.size == job.rank) {
                    SurfaceOrigin origin;
                    obtain_surface(*c.ndf, realisation(c.surface, r), settings.cache,
                                   settings.threads, origin);
                }
        mpi_barrier();
        const std::vector<long long> first = first_units(cfg);
        std::vector<StoredUnit> mine;
        for (size_t ci = 0; ci < cfg.cases.size(); ++ci) {
            const size_t np = cfg.cases[ci].phi_i_deg.size();
            UnitPlan plan;
            plan.trace_only = true;
            plan.owned = [&](size_t ti, size_t pi) {
                return (first[ci] + (long long)(ti * np + pi)) % job.size == job.rank;
            };
            plan.traced = [&](size_t ti, size_t pi, const UnitTraces& u) {
                mine.push_back({first[ci] + (long long)(ti * np + pi), ci, ti, pi, u});
            };
            plan.stop_requested = [] { return stop_requested(); };
            settings.case_index = ci;
            settings.plan = &plan;
            simulate_case(cfg.cases[ci], settings);
        }
        if (job.rank != 0) {
            mpi_send_units(mine);
            return 0;
        }
        std::vector<StoredUnit> all = mpi_receive_units();
        for (StoredUnit& u : mine) all.push_back(std::move(u));
        std::vector<std::map<IncidenceKey, UnitTraces>> done(cfg.cases.size());
        for (StoredUnit& u : all)
            done[u.case_index][{u.theta_index, u.phi_index}] = std::move(u.traces);
        return assemble_and_write(cfg, o, output, done, nullptr, run, start, job.size, 0);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gonio: error (rank %d of %d): %s\n", job.rank, job.size, e.what());
        mpi_abort(1);
    }
}
} // namespace

int run_run_command(const RunOptions& o) {
    const auto start = PhaseTimes::Clock::now();
    const Config cfg = load_config(o.config, o.overrides); // throws ConfigError
    cfg.require_beam("gonio run");
    PhaseTimes run = run_phases(cfg, start);
    const auto limit = limit_threads(o.threads);
    const std::string output =
        o.output.empty() ? std::filesystem::path(o.config).stem().string() + ".h5" : o.output;
    install_stop_handlers();
    if (mpi_job().active()) return run_mpi(cfg, o, output, run, start);
    if (o.shard == "slurm" && !shard_from_environment().active())
        throw std::runtime_error(
            "--shard slurm: SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT are "
            "not set (not a task of a Slurm job array)");
    const Shard shard = o.shard.empty()      ? Shard{}
                        : o.shard == "slurm" ? shard_from_environment()
                                             : parse_shard(o.shard);
    if (shard.active() && o.resume)
        throw std::runtime_error("--resume with --shard: a shard keeps no checkpoint; run the "
                                 "shard again");
    try {
        if (shard.active()) return run_shard(cfg, o, shard, output);

        // A checkpoint beside the output: every finished incidence, flushed; --resume reads it.
        const std::string checkpoint = output + ".checkpoint";
        const UnitFileHeader header = unit_header(cfg, o.command_line);
        const std::vector<long long> first = first_units(cfg);
        std::vector<std::map<IncidenceKey, UnitTraces>> done(cfg.cases.size());
        const bool resuming = o.resume && std::filesystem::exists(checkpoint);
        if (o.resume && !resuming)
            throw std::runtime_error(checkpoint +
                                     ": no checkpoint to resume (run without --resume)");
        if (!o.resume && std::filesystem::exists(checkpoint) && !o.overwrite)
            throw std::runtime_error(checkpoint +
                                     ": an interrupted run's checkpoint; pass --resume "
                                     "to continue it or --overwrite to start again");
        if (!o.overwrite && std::filesystem::exists(output))
            throw std::runtime_error(output + ": exists; pass --overwrite to replace it");
        if (resuming) {
            UnitFileHeader saved;
            for (StoredUnit& u : read_unit_file(checkpoint, &saved)) {
                if (u.case_index >= done.size())
                    throw std::runtime_error(checkpoint + ": a unit of no case of this config");
                done[u.case_index][{u.theta_index, u.phi_index}] = std::move(u.traces);
            }
            if (const std::string why = saved.differs_from(header); !why.empty())
                throw std::runtime_error(checkpoint + ": a checkpoint of another run (" + why +
                                         "); it was left as it is");
            long long n = 0;
            for (const auto& d : done) n += (long long)d.size();
            if (!o.quiet)
                std::printf("resuming %s: %lld of %lld incidences done\n", checkpoint.c_str(), n,
                            header.units_total);
        }
        const auto opened = PhaseTimes::Clock::now();
        UnitFileWriter ckpt(checkpoint, header, resuming);
        run.add_since("checkpoint", opened);
        long long added = 0;
        auto traced = [&](size_t ci, size_t ti, size_t pi, const UnitTraces& u) {
            const size_t np = cfg.cases[ci].phi_i_deg.size();
            ckpt.add({first[ci] + (long long)(ti * np + pi), ci, ti, pi, u});
            ++added;
        };
        int code = 0;
        try {
            code = assemble_and_write(cfg, o, output, done, traced, run, start, 1, 0);
        } catch (const Interrupted&) {
            throw;
        } catch (...) { // a failure before any incidence leaves no checkpoint to trip over
            ckpt.close();
            if (added == 0 && !resuming) std::filesystem::remove(checkpoint);
            throw;
        }
        ckpt.close();
        std::filesystem::remove(checkpoint);
        return code;
    } catch (const Interrupted&) {
        if (shard.active())
            std::fprintf(stderr, "gonio: interrupted; shard %s wrote nothing (run it again)\n",
                         shard.text().c_str());
        else
            std::fprintf(stderr,
                         "gonio: interrupted; the finished incidences are in %s.checkpoint: `gonio "
                         "run ... --resume` continues the run\n",
                         output.c_str());
        return 130;
    }
}

int run_merge_command(const std::vector<std::string>& parts, const std::string& output,
                      bool overwrite, bool quiet, int threads) {
    const auto start = PhaseTimes::Clock::now();
    UnitFileHeader first;
    std::map<long long, std::string> owner; // unit -> the part that holds it
    std::vector<StoredUnit> units;
    std::map<int, std::pair<std::string, StoredUnit>> batch_parts; // shard index -> its part
    int batch_count = 0;
    for (size_t k = 0; k < parts.size(); ++k) {
        UnitFileHeader h;
        std::vector<StoredUnit> got = read_unit_file(parts[k], &h);
        if (k == 0)
            first = h;
        else if (const std::string why = h.differs_from(first); !why.empty())
            throw std::runtime_error(parts[k] + ": a part of another run than " + parts[0] + " (" +
                                     why + ")");
        if (h.by_batches) { // a single-incidence job: the parts hold shares of the batches
            const Shard sh = parse_shard(h.shard);
            if (batch_count != 0 && sh.count != batch_count)
                throw std::runtime_error(parts[k] + ": shard " + sh.text() + " of a split into " +
                                         std::to_string(sh.count) + ", the others into " +
                                         std::to_string(batch_count));
            batch_count = sh.count;
            const auto [it, fresh] =
                batch_parts.emplace(sh.index, std::make_pair(parts[k], StoredUnit{}));
            if (!fresh)
                throw std::runtime_error("shard " + sh.text() + " is in both " + it->second.first +
                                         " and " + parts[k] + " (a part given twice?)");
            if (got.size() != 1)
                throw std::runtime_error(parts[k] + ": a batch shard without its unit");
            it->second.second = std::move(got[0]);
            continue;
        }
        for (StoredUnit& u : got) {
            const auto [it, fresh] = owner.emplace(u.unit, parts[k]);
            if (!fresh)
                throw std::runtime_error("unit " + std::to_string(u.unit) + " is in both " +
                                         it->second + " and " + parts[k] +
                                         " (a part given twice?)");
            units.push_back(std::move(u));
        }
    }
    if (!batch_parts.empty()) {
        std::string missing;
        for (int i = 0; i < batch_count; ++i)
            if (!batch_parts.count(i)) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
        if (!missing.empty())
            throw std::runtime_error("the batch shards " + missing + " of " +
                                     std::to_string(batch_count) +
                                     " are in none of the parts: a part is missing");
        std::vector<TraceResult> traces;
        for (auto& [i, part] : batch_parts) traces.push_back(part.second.traces.members.at(0));
        StoredUnit u = batch_parts.begin()->second.second;
        u.traces.members = {combine_batch_shards(traces)};
        owner.emplace(u.unit, "the batch shards");
        units.push_back(std::move(u));
    }
    std::string missing;
    long long count = 0;
    for (long long u = 0; u < first.units_total; ++u)
        if (!owner.count(u) && ++count <= 8)
            missing += (missing.empty() ? "" : ", ") + std::to_string(u);
    if (count > 0)
        throw std::runtime_error(std::to_string(count) + " of " +
                                 std::to_string(first.units_total) +
                                 " units are in none of the parts (" + missing +
                                 (count > 8 ? ", ..." : "") + "): a part is missing");
    std::vector<std::string> overrides;
    {
        std::string line;
        for (char ch : first.overrides)
            if (ch == '\n')
                overrides.push_back(line), line.clear();
            else
                line += ch;
    }
    Config cfg = parse_config(first.effective_toml, first.config_path);
    cfg.text = first.config_toml;
    cfg.overrides = overrides;
    std::vector<std::map<IncidenceKey, UnitTraces>> done(cfg.cases.size());
    for (StoredUnit& u : units) {
        if (u.case_index >= done.size())
            throw std::runtime_error("a unit of no case of the stored config");
        done[u.case_index][{u.theta_index, u.phi_index}] = std::move(u.traces);
    }
    RunOptions o;
    o.overwrite = overwrite;
    o.quiet = quiet;
    o.threads = threads;
    o.command_line = first.command_line;
    const auto limit = limit_threads(threads);
    PhaseTimes run = run_phases(cfg, start);
    return assemble_and_write(cfg, o, output, done, nullptr, run, start, 1, int(parts.size()));
}

} // namespace gonio
