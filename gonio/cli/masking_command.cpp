// `gonio masking CONFIG [-o OUT.h5]`: the masking and shadowing of every case's explicit surfaces,
// measured by ray casting and held against Smith's forms (gonio/masking/masking_run.h).
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/cli/progress.h"
#include "gonio/masking/masking_run.h"

#include <cmath>
#include <cstdio>
#include <mutex>

namespace gonio {

namespace {
struct MaskingArgs {
    CommonOptions common;
    MaskingOptions options;
};

// One line per w: the weak furnace against cos theta_o, and the projected-area G1 against Smith's
// from the analytic NDF and from D_s; then G2 at the retro direction and the specular plane.
void print_case(const CaseMasking& c) {
    const MaskingEstimates& e = c.estimates;
    std::printf("%s: %s; %d surface%s, %lld points\n", c.name.c_str(), c.ndf.c_str(), e.surfaces,
                e.surfaces > 1 ? "s" : "", e.points);
    std::printf("  %7s %7s %18s %8s %8s %18s %11s %11s\n", "theta_o", "phi_o", "furnace", "cos",
                "z", "G1 (projected)", "Smith NDF", "Smith D_s");
    const Array &f = e["furnace"], &fe = e["furnace_stderr"], &z = e["furnace_z"],
                &g = e["g1_projected"], &ge = e["g1_projected_stderr"], &sn = e["g1_smith_ndf"],
                &ss = e["g1_smith_surface"];
    for (size_t t = 0; t < e.theta_o.size(); ++t)
        for (size_t p = 0; p < e.phi_o.size(); ++p) {
            const size_t k = t * e.phi_o.size() + p;
            std::printf("  %7g %7g %10.6f±%.1e %8.6f %+8.2f %10.6f±%.1e %11.6f %11.6f\n",
                        e.theta_o[t], e.phi_o[p], f.data[k], fe.data[k],
                        std::cos(radians(e.theta_o[t])), z.data[k], g.data[k], ge.data[k],
                        sn.data[k], ss.data[k]);
        }
    if (e.theta_i.empty()) return;
    const Array &g2 = e["g2"], &g2e = e["g2_stderr"], &u = e["g2_smith_uncorrelated_surface"],
                &hc = e["g2_smith_height_correlated_surface"],
                &hd = e["g2_smith_height_direction_correlated_surface"];
    std::printf("  G2 against Smith's forms (Lambda of D_s): retro (wo = wi) and specular plane\n");
    std::printf("  %7s %7s %9s %7s %18s %10s %10s %10s\n", "theta_i", "phi_i", "theta_o", "dphi",
                "G2", "uncorr", "height", "height-dir");
    const size_t n2t = e.g2_theta_o.size(), n2p = e.g2_dphi.size();
    for (size_t i = 0; i < e.theta_i.size() * e.phi_i.size(); ++i)
        for (size_t t = 0; t < n2t; ++t)
            for (size_t p = 0; p < n2p; ++p) {
                const bool retro =
                    e.g2_theta_o[t] == e.theta_i[i / e.phi_i.size()] && e.g2_dphi[p] == 0;
                const bool specular =
                    e.g2_theta_o[t] == e.theta_i[i / e.phi_i.size()] && e.g2_dphi[p] == 180;
                if ((!retro && !specular) || (specular && e.g2_theta_o[t] == 0)) continue;
                const size_t k = (i * n2t + t) * n2p + p;
                std::printf("  %7g %7g %9g %7g %10.6f±%.1e %10.6f %10.6f %10.6f\n",
                            e.theta_i[i / e.phi_i.size()], e.phi_i[i % e.phi_i.size()],
                            e.g2_theta_o[t], e.g2_dphi[p], g2.data[k], g2e.data[k], u.data[k],
                            hc.data[k], hd.data[k]);
            }
}

int masking(MaskingArgs& a, const CliContext& context) {
    const Config cfg = load_config(a.common.config, a.common.overrides); // throws ConfigError
    const auto limit = limit_threads(a.common.threads);
    const std::string output = output_or_default(a.common.output, a.common.config, "_masking.h5");
    refuse_existing(output, a.common.overwrite);
    const SurfaceCache cache = surface_cache(a.common);
    MaskingOptions& o = a.options;
    o.cache = &cache;
    o.threads = a.common.threads;
    Progress progress(1000, a.common.quiet);
    std::mutex lock;
    o.progress = [&](const std::string& label, double fraction) {
        std::lock_guard<std::mutex> guard(lock);
        progress.update(static_cast<long long>(1000 * fraction), label);
    };
    const std::vector<CaseMasking> cases = run_masking(cfg, o);
    progress.finish();
    write_masking_file(output, a.common.overwrite, cfg, context.command_line, o, cases);
    if (!a.common.quiet) {
        for (const CaseMasking& c : cases) print_case(c);
        std::printf("wrote %s\n", output.c_str());
    }
    return 0;
}

std::function<int()> setup(CLI::App& app, const CliContext& context) {
    auto a = std::make_shared<MaskingArgs>();
    add_common_options(app, a->common, kConfig | kSet | kOverwrite | kQuiet | kThreads | kCache);
    app.add_option("-o,--output", a->common.output,
                   "HDF5 masking file (default: <config>_masking.h5)");
    app.add_option("--points", a->options.points, "Points per surface (default 131072)")
        ->check(CLI::Range(1LL << 10, 1LL << 30));
    app.add_option("--g2-points", a->options.g2_points,
                   "Of them, the points G2 is measured on (default 16384)")
        ->check(CLI::Range(1LL << 6, 1LL << 30));
    app.add_option("--normal-bins", a->options.normal_bins,
                   "Equal-area bins of the facet normal (default 145)")
        ->check(CLI::Range(1, 10000));
    app.add_option("--height-bins", a->options.height_bins,
                   "Quantiles of the points' heights (default 8)")
        ->check(CLI::Range(1, 1000));
    return [a, context] { return masking(*a, context); };
}
} // namespace

const Command& masking_command() {
    static const Command c{
        "masking", "Measure the masking and shadowing of every case's surfaces against Smith's",
        setup};
    return c;
}

} // namespace gonio
