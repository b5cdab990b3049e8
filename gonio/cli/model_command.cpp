#include "gonio/cli/cli_common.h"
#include "gonio/cli/commands.h"
#include "gonio/cli/progress.h"
#include "gonio/config/config.h"
#include "gonio/config/config_error.h"
#include "gonio/io/result_writer.h"
#include "gonio/model/case_models.h"
#include "heightfield/surface_source.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
namespace gonio {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}
std::string default_output(const std::string& config) {
    std::filesystem::path p(config);
    return p.stem().string() + ".h5";
}
} // namespace

int run_model_command(const ModelOptions& options) {
    const auto wall = Clock::now();
    const Config cfg = load_config(options.config, options.overrides); // throws ConfigError
    for (size_t k = 0; k < cfg.cases.size(); ++k)
        if (cfg.cases[k].models.empty())
            throw ConfigError(cfg.path, -1, "case[" + std::to_string(k) + "].model.evaluate",
                              "gonio model evaluates the models; this case has none");
    const std::string output =
        options.output.empty() ? default_output(options.config) : options.output;
    const auto limit = limit_threads(options.threads);

    ResultWriter writer(output, options.overwrite); // refuses to replace a file before any work
    writer.write_run(cfg, options.command_line);

    long long total = 0, done = 0;
    for (const auto& c : cfg.cases) total += c.theta_i_deg.size() * c.phi_i_deg.size();
    Progress progress(total, options.quiet);
    if (!options.quiet)
        std::printf("%-24s %8s %8s  %-10s %s\n", "case", "theta_i", "phi_i", "model", "albedo");

    for (size_t ci = 0; ci < cfg.cases.size(); ++ci) {
        const CaseConfig& c = cfg.cases[ci];
        auto t0 = Clock::now();
        const BeckersSensor sensor(c.sensor_cells);
        const auto ndf = make_ndf(c.ndf);
        // The P-BRDF is fitted to the surface's slopes: made (or taken from the default cache).
        HeightField surface;
        if (c.needs_surface()) {
            SurfaceOrigin origin;
            surface = obtain_surface(*ndf, c.surface, surface_cache(false, ""),
                                     worker_threads(options.threads), origin);
        }
        CaseModels models(c, *ndf, c.needs_surface() ? &surface : nullptr);
        std::vector<std::pair<std::string, double>> phases{{"setup", since(t0)}};
        t0 = Clock::now();
        for (size_t ti = 0; ti < c.theta_i_deg.size(); ++ti) {
            for (size_t pi = 0; pi < c.phi_i_deg.size(); ++pi) {
                const double theta = c.theta_i_deg[ti], phi = c.phi_i_deg[pi];
                char label[160];
                std::snprintf(label, sizeof label, "%s theta_i=%g phi_i=%g", c.name.c_str(), theta,
                              phi);
                progress.update(done, label);
                const Vec3 wi = spherical_direction(radians(theta), radians(phi));
                // The same streams as gonio run's, so V-cavity estimates agree between the two.
                const std::uint64_t stream =
                    (std::uint64_t(ci) << 40) ^ (std::uint64_t(ti) << 20) ^ std::uint64_t(pi);
                const auto albedos = models.evaluate(wi, sensor, cfg.seed, stream);
                ++done;
                if (!options.quiet) {
                    progress.finish();
                    for (size_t m = 0; m < albedos.size(); ++m) {
                        std::printf("%-24s %8.3f %8.3f  %-10s", c.name.c_str(), theta, phi,
                                    c.models[m].c_str());
                        for (double a : albedos[m]) std::printf(" %.6f", a);
                        std::printf("\n");
                    }
                }
            }
        }
        phases.emplace_back("models", since(t0));
        t0 = Clock::now();
        writer.write_model_case(c, sensor, ndf->describe(), models.results());
        phases.emplace_back("write", since(t0));
        writer.write_timings(c.name, phases);
    }
    progress.finish();
    writer.write_timings("", {{"wall", since(wall)}});
    writer.commit();
    if (!options.quiet) std::printf("wrote %s\n", output.c_str());
    return 0;
}

} // namespace gonio
