#include "core/config_error.h"
#include "gonio/cli/cli_common.h"
#include "gonio/cli/commands.h"
#include "gonio/cli/progress.h"
#include "gonio/config/config.h"
#include "gonio/distributed/stop_signal.h"
#include "gonio/distributed/work_units.h"
#include "gonio/io/result_writer.h"
#include "gonio/pipeline/simulate_case.h"

#include <cstdio>
#include <filesystem>

namespace gonio {

int run_model_command(const ModelOptions& options) {
    const auto start = PhaseTimes::Clock::now();
    const Config cfg = load_config(options.config, options.overrides); // throws ConfigError
    cfg.require_beam("gonio model");
    for (size_t k = 0; k < cfg.cases.size(); ++k)
        if (cfg.cases[k].model.models.empty())
            throw ConfigError(cfg.path, -1, "case[" + std::to_string(k) + "].model.evaluate",
                              "gonio model evaluates the models; this case has none");
    PhaseTimes run = run_phases(cfg, start);
    auto t = PhaseTimes::Clock::now();
    const std::string output = options.output.empty()
                                   ? std::filesystem::path(options.config).stem().string() + ".h5"
                                   : options.output;
    const auto limit = limit_threads(options.threads);
    install_stop_handlers();
    ResultWriter writer(output, options.overwrite); // refuses to replace a file before any work
    writer.write_run(cfg, options.command_line);
    t = run.add_since("writing", t);

    long long total = 0, done = 0;
    for (const auto& c : cfg.cases) total += c.theta_i_deg.size() * c.phi_i_deg.size();
    Progress progress(total, options.quiet);
    if (!options.quiet)
        std::printf("%-24s %8s %8s  %-10s %s\n", "case", "theta_i", "phi_i", "model", "albedo");
    CaseRunSettings settings;
    settings.seed = cfg.seed;
    settings.threads = worker_threads(options.threads);
    settings.cache = surface_cache(false, ""); // the P-BRDF's surface, from the default cache
    for (size_t ci = 0; ci < cfg.cases.size(); ++ci) {
        const CaseConfig& c = cfg.cases[ci];
        CaseObserver observer;
        observer.started = [&](const std::string& label) {
            if (stop_requested()) throw Interrupted(); // between incidences: nothing half-written
            progress.update(done, label);
        };
        observer.finished = [&](const IncidenceReport& r) {
            ++done;
            if (options.quiet) return;
            progress.finish();
            for (size_t m = 0; m < r.model_albedos->size(); ++m) {
                std::printf("%-24s %8.3f %8.3f  %-10s", c.name.c_str(), r.theta_deg, r.phi_deg,
                            c.model.models[m].name.c_str());
                for (double a : (*r.model_albedos)[m]) std::printf(" %.6f", a);
                std::printf("\n");
            }
        };
        settings.case_index = ci;
        CaseResult result;
        try {
            result = evaluate_case_models(c, settings, observer);
        } catch (const Interrupted&) {
            progress.finish();
            std::fprintf(stderr, "gonio: interrupted; nothing was written (models are recomputed "
                                 "on the next run)\n");
            return 130;
        }
        t = PhaseTimes::Clock::now();
        writer.write_model_case(c, *result.sensor, c.ndf->describe(), result.models);
        PhaseTimes phases = result.phases;
        phases.add_since("writing", t);
        writer.write_timings(c.name, phases.phases());
        run.merge(phases);
        t = PhaseTimes::Clock::now();
    }
    progress.finish();
    run.add_since("writing", t);
    finish_run(writer, run, start);
    if (!options.quiet) std::printf("wrote %s\n", output.c_str());
    return 0;
}

} // namespace gonio
