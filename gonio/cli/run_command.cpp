#include "gonio/cli/cli_common.h"
#include "gonio/cli/commands.h"
#include "gonio/cli/progress.h"
#include "gonio/config/config.h"
#include "gonio/io/result_writer.h"
#include "gonio/material/facet_materials.h"
#include "gonio/model/case_models.h"
#include "gonio/trace/gonioreflectometer.h"
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
} // namespace

int run_run_command(const RunOptions& o) {
    const auto wall = Clock::now();
    const Config cfg = load_config(o.config, o.overrides); // throws ConfigError
    const auto limit = limit_threads(o.threads);
    const int threads = worker_threads(o.threads);
    const std::string output =
        o.output.empty() ? std::filesystem::path(o.config).stem().string() + ".h5" : o.output;
    ResultWriter writer(output, o.overwrite); // an existing or unwritable output fails here
    writer.write_run(cfg, o.command_line);
    const SurfaceCache cache = surface_cache(o.no_cache, o.cache_dir);
    long long total = 0, done = 0;
    for (const auto& c : cfg.cases) total += c.theta_i_deg.size() * c.phi_i_deg.size();
    if (!o.quiet)
        std::printf("%-20s %7s %7s %10s %8s %10s %10s %7s %10s %10s %9s\n", "case", "theta_i",
                    "phi_i", "L1", "+-", "model", "rel_diff", "sigmas", "L2+", "T", "lost");
    for (size_t ci = 0; ci < cfg.cases.size(); ++ci) {
        const CaseConfig& c = cfg.cases[ci];
        // Wall time per phase of the case, in the order they run.
        std::vector<std::pair<std::string, double>> phases{
            {"surface", 0}, {"setup", 0}, {"trace", 0}, {"models", 0}, {"write", 0}};
        auto t0 = Clock::now();
        const auto ndf = make_ndf(c.ndf);
        SurfaceOrigin origin;
        const HeightField surface = obtain_surface(*ndf, c.surface, cache, threads, origin);
        phases[0].second = since(t0);
        t0 = Clock::now();
        if (!origin.warning.empty())
            std::fprintf(stderr, "gonio: warning: %s\n", origin.warning.c_str());
        const Scene scene(surface); // one surface per case: sweeps never regenerate it
        const BeckersSensor sensor(c.sensor_cells);
        const auto materials = facet_materials(c);
        std::vector<const Material*> parts;
        for (const auto& m : materials) parts.push_back(m.get());
        const bool transmits = materials[0]->transmits();
        CaseModels models(c, *ndf, &surface);
        // The terminal shows the first model of single scattering next to L1 (all are in the file).
        int shown = -1;
        for (size_t m = 0; m < c.models.size() && shown < 0; ++m)
            if (models.results()[m].compared_with == "l1") shown = int(m);
        const int nc = c.channels();
        SimulationResult sim(c.theta_i_deg, c.phi_i_deg, sensor);
        sim.surface = origin.loaded ? c.surface.input : origin.cache_path;
        phases[1].second = since(t0);
        Progress progress(total, o.quiet);
        for (size_t ti = 0; ti < c.theta_i_deg.size(); ++ti) {
            for (size_t pi = 0; pi < c.phi_i_deg.size(); ++pi) {
                char label[160];
                std::snprintf(label, sizeof label, "%s theta_i=%g phi_i=%g", c.name.c_str(),
                              c.theta_i_deg[ti], c.phi_i_deg[pi]);
                progress.update(done, label);
                const Vec3 wi =
                    spherical_direction(radians(c.theta_i_deg[ti]), radians(c.phi_i_deg[pi]));
                TraceSettings st;
                st.rays = c.rays;
                st.orders = c.orders;
                st.max_bounces = c.max_bounces;
                st.batches = c.batches;
                st.target = c.target;
                st.seed = cfg.seed;
                st.stream =
                    (std::uint64_t(ci) << 40) ^ (std::uint64_t(ti) << 20) ^ std::uint64_t(pi);
                t0 = Clock::now();
                const TraceResult r = trace_incidence(scene, parts, sensor, wi, st);
                phases[2].second += since(t0);
                t0 = Clock::now();
                // The models' V-cavity paths draw from their own streams (key "VCAVITY").
                models.evaluate(wi, sensor, cfg.seed, st.stream);
                std::vector<Comparison> comparisons;
                for (size_t m = 0; m < c.models.size(); ++m)
                    comparisons.push_back(compare_model(
                        r, models.results()[m].compared_with == "linf", models.last(m)));
                phases[3].second += since(t0);
                sim.append(r, comparisons);
                ++done;
                if (!o.quiet) {
                    progress.finish();
                    for (size_t k = 0; k < size_t(nc); ++k) {
                        const Estimate& l1 = sim.reflected.first_albedo;
                        std::printf("%-20s %7.2f %7.2f %10.6f %8.1e", c.name.c_str(),
                                    c.theta_i_deg[ti], c.phi_i_deg[pi], l1.mean.at({ti, pi, k}),
                                    l1.error.at({ti, pi, k}));
                        if (shown >= 0) {
                            const Comparison& cmp = comparisons[size_t(shown)];
                            std::printf(" %10.6f %+10.4f %+7.1f", cmp.model_albedo[k],
                                        cmp.relative_difference[k], cmp.sigmas[k]);
                        } else
                            std::printf(" %10s %10s %7s", "-", "-", "-");
                        std::printf(" %10.6f", sim.reflected.higher_albedo.mean.at({ti, pi, k}));
                        if (transmits)
                            std::printf(" %10.6f", sim.transmitted.all_albedo.mean.at({ti, pi, k}));
                        else
                            std::printf(" %10s", "-");
                        std::printf(" %9.2e", sim.lost.mean.at({ti, pi, k}));
                        if (c.target.active())
                            std::printf("  %s: %.2e with %lld rays", r.stop.c_str(),
                                        r.achieved_error, r.rays);
                        std::printf("\n");
                    }
                }
            }
        }
        progress.finish();
        t0 = Clock::now();
        writer.write_simulation_case(c, sensor, ndf->describe(), sim, models.results());
        phases[4].second = since(t0);
        writer.write_timings(c.name, phases);
    }
    writer.write_timings("", {{"wall", since(wall)}});
    writer.commit();
    if (!o.quiet) std::printf("wrote %s\n", output.c_str());
    return 0;
}

} // namespace gonio
