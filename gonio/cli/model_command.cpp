// `gonio model CONFIG`: the models of every case and incidence on the sensor cells, without a
// trace, written to HDF5.
#include "core/config_error.h"
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/cli/progress.h"
#include "gonio/cli/stop_signal.h"
#include "gonio/io/result_writer.h"
#include "gonio/run/run.h"

#include <cstdio>

namespace gonio {

namespace {
int model(const CommonOptions& a, const CliContext& context) {
    const auto start = PhaseTimes::Clock::now();
    const Config cfg = load_config(a.config, a.overrides); // throws ConfigError
    cfg.require_beam("gonio model");
    for (size_t k = 0; k < cfg.cases.size(); ++k)
        if (cfg.cases[k].model.models.empty())
            throw ConfigError(cfg.path, -1, "case[" + std::to_string(k) + "].model.evaluate",
                              "gonio model evaluates the models; this case has none");
    const auto limit = limit_threads(a.threads);
    const std::string output = output_or_default(a.output, a.config, ".h5");
    refuse_existing(output, a.overwrite);
    ResultWriter writer(output, true); // an unwritable output fails here, before any work
    install_stop_handlers();
    RunOptions o = run_options(a, context, start); // its cache: the P-BRDF's surface
    Progress progress(UnitLayout(cfg).total(), a.quiet);
    long long done = 0;
    if (!a.quiet)
        std::printf("%-24s %8s %8s  %-10s %s\n", "case", "theta_i", "phi_i", "model", "albedo");
    o.observer.started = [&](const std::string& label) { progress.update(done, label); };
    o.observer.incidence = [&](const IncidenceReport& r) {
        ++done;
        if (a.quiet) return;
        progress.finish();
        for (size_t m = 0; m < r.models->size(); ++m) {
            std::printf("%-24s %8.3f %8.3f  %-10s", r.config->name.c_str(), r.theta_deg, r.phi_deg,
                        r.config->model.models[m].name.c_str());
            for (double v : albedo_from_cells((*r.models)[m].energy, r.config->channels()))
                std::printf(" %.6f", v);
            std::printf("\n");
        }
    };
    o.observer.warn = [&](const std::string& w) {
        if (a.quiet) return;
        progress.finish();
        std::fprintf(stderr, "gonio: warning: %s\n", w.c_str());
    };
    RunResult result;
    try {
        result = run_models(cfg, o);
    } catch (const Interrupted&) {
        progress.finish();
        std::fprintf(stderr, "gonio: interrupted; nothing was written (models are recomputed "
                             "on the next run)\n");
        return 130;
    }
    progress.finish();
    write_result(result, writer);
    if (!a.quiet) std::printf("wrote %s\n", output.c_str());
    return 0;
}

std::function<int()> setup(CLI::App& app, const CliContext& context) {
    auto a = std::make_shared<CommonOptions>();
    add_common_options(app, *a, kConfig | kSet | kOverwrite | kQuiet | kThreads | kCacheDir);
    app.add_option("-o,--output", a->output, "HDF5 result file (default: <config>.h5)");
    return [a, context] { return model(*a, context); };
}
} // namespace

const Command& model_command() {
    static const Command c{
        "model", "Evaluate the analytic Model L1 on the sensor cells for every case and incidence",
        setup};
    return c;
}

} // namespace gonio
