#include "gonio/cli/cli_common.h"
#include "gonio/cli/commands.h"
#include "gonio/cli/progress.h"
#include "gonio/config/config.h"
#include "gonio/config/config_error.h"
#include "gonio/io/result_writer.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/microfacet_model.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
namespace gonio {

namespace {
std::string default_output(const std::string& config) {
    std::filesystem::path p(config);
    return p.stem().string() + ".h5";
}
} // namespace

int run_model_command(const ModelOptions& options) {
    const Config cfg = load_config(options.config, options.overrides); // throws ConfigError
    for (size_t k = 0; k < cfg.cases.size(); ++k)
        if (cfg.cases[k].diffuse())
            throw ConfigError(cfg.path, -1, "case[" + std::to_string(k) + "].material.type",
                              "Model L1 is the specular microfacet BRDF; \"" +
                                  cfg.cases[k].material_type + "\" facets have no model here yet");
    const std::string output =
        options.output.empty() ? default_output(options.config) : options.output;
    const auto limit = limit_threads(options.threads);

    ResultWriter writer(output, options.overwrite); // refuses to replace a file before any work
    writer.write_run(cfg, options.command_line);

    long long total = 0, done = 0;
    for (const auto& c : cfg.cases) total += c.theta_i_deg.size() * c.phi_i_deg.size();
    Progress progress(total, options.quiet);
    if (!options.quiet)
        std::printf("%-24s %8s %8s  %s\n", "case", "theta_i", "phi_i", "model_l1_albedo");

    for (const CaseConfig& c : cfg.cases) {
        const BeckersSensor sensor(c.sensor_cells);
        const auto ndf = make_ndf(c.ndf);
        const MicrofacetModel model(*ndf, c.fresnel, c.masking);
        const int nc = model.channels();
        ModelL1Result result;
        for (double theta : c.theta_i_deg) {
            for (double phi : c.phi_i_deg) {
                char label[160];
                std::snprintf(label, sizeof label, "%s theta_i=%g phi_i=%g", c.name.c_str(), theta,
                              phi);
                progress.update(done, label);
                const auto t0 = std::chrono::steady_clock::now();
                const Vec3 wi = spherical_direction(radians(theta), radians(phi));
                const std::vector<double> energy =
                    model_cell_energy(model, wi, sensor, c.quadrature);
                const std::vector<double> albedo = albedo_from_cells(energy, nc);
                result.seconds.push_back(
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
                result.energy.insert(result.energy.end(), energy.begin(), energy.end());
                result.albedo.insert(result.albedo.end(), albedo.begin(), albedo.end());
                ++done;
                if (!options.quiet) {
                    progress.finish();
                    std::printf("%-24s %8.3f %8.3f ", c.name.c_str(), theta, phi);
                    for (double a : albedo) std::printf(" %.6f", a);
                    std::printf("\n");
                }
            }
        }
        writer.write_model_case(c, sensor, result);
    }
    progress.finish();
    writer.commit();
    if (!options.quiet) std::printf("wrote %s\n", output.c_str());
    return 0;
}

} // namespace gonio
