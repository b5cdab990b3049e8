#include "gonio/cli/cli_common.h"
#include "gonio/cli/commands.h"
#include "gonio/cli/progress.h"
#include "gonio/config/config.h"
#include "gonio/io/result_writer.h"
#include "gonio/pipeline/simulate_case.h"

#include <cstdio>
#include <filesystem>

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
} // namespace

int run_run_command(const RunOptions& o) {
    const auto start = PhaseTimes::Clock::now();
    const Config cfg = load_config(o.config, o.overrides); // throws ConfigError
    cfg.require_beam("gonio run");
    PhaseTimes run = run_phases(cfg, start);
    auto t = PhaseTimes::Clock::now();
    const auto limit = limit_threads(o.threads);
    const std::string output =
        o.output.empty() ? std::filesystem::path(o.config).stem().string() + ".h5" : o.output;
    ResultWriter writer(output, o.overwrite); // an existing or unwritable output fails here
    writer.write_run(cfg, o.command_line);
    t = run.add_since("writing", t);

    long long total = 0, done = 0;
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
        observer.started = [&](const std::string& label) { progress.update(done, label); };
        observer.finished = [&](const IncidenceReport& r) {
            ++done;
            if (o.quiet) return;
            progress.finish();
            print_incidence(c, r, shown);
        };
        observer.warn = [](const std::string& w) {
            std::fprintf(stderr, "gonio: warning: %s\n", w.c_str());
        };
        settings.case_index = ci;
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

} // namespace gonio
