// `gonio fit RESULT.h5 --model FAMILY [...] [-o FIT.toml|FIT.json]`: the analytic model's
// parameters that reproduce a case, with error bars (gonio/fit/fit.h).
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/cli/progress.h"
#include "gonio/fit/fit.h"
#include "heightfield/ndf/ndf_family.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace gonio {

namespace {
struct FitArgs {
    std::string file, output, orders, with = "none", fresnel = "fixed", loss = "chi2";
    FitOptions options;
    bool quiet = false, overwrite = false;
    int threads = 0;
};

int fit(FitArgs& a) {
    FitOptions& o = a.options;
    o.with = enum_named<FitWith>(a.with); // CLI11 checked the names
    o.fresnel = enum_named<FitFresnel>(a.fresnel);
    o.loss = enum_named<FitLoss>(a.loss);
    o.orders = a.orders.empty() ? (o.with == FitWith::none ? FitOrders::l1 : FitOrders::linf)
                                : enum_named<FitOrders>(a.orders);
    if (o.with != FitWith::none && o.orders == FitOrders::l1)
        throw UsageError("--with " + a.with +
                         " models every order: fit it to --orders linf (the default with --with)");
    if (!a.output.empty()) {
        const std::string ext = std::filesystem::path(a.output).extension().string();
        if (ext != ".toml" && ext != ".json")
            throw UsageError("-o " + a.output + ": the fit is written as .toml or .json");
        refuse_existing(a.output, a.overwrite);
    }
    const auto limit = limit_threads(a.threads);
    Progress progress(1, a.quiet);
    const FitResult r = fit_result_case(a.file, o, [&](int done, int total) {
        progress.update(done * 1000LL / total,
                        "fit " + std::to_string(done) + "/" + std::to_string(total));
    });
    progress.finish();
    if (!a.quiet) {
        std::printf("%s, case %s: %s fitted to %s (%s loss, %lld points)\n", r.file.c_str(),
                    r.case_name.c_str(), r.family.c_str(), r.data.c_str(), a.loss.c_str(),
                    r.points);
        std::printf("%-12s %14s %14s %14s %14s\n", "parameter", "value", "stderr", "bootstrap",
                    "bounds");
        for (size_t k = 0; k < r.names.size(); ++k) {
            char boot[32] = "-", bounds[48];
            if (!r.stderr_bootstrap.empty())
                std::snprintf(boot, sizeof boot, "%.3g", r.stderr_bootstrap[k]);
            std::snprintf(bounds, sizeof bounds, "[%g, %g]", r.lower[k], r.upper[k]);
            std::printf("%-12s %14.6f %14.3g %14s %14s\n", r.names[k].c_str(), r.value[k],
                        r.stderr_covariance[k], boot, bounds);
        }
        std::printf("chi2/dof %.4g (chi2 %.6g over %lld points - %zu parameters); %d of %d starts "
                    "converged; %.1f s\n",
                    r.chi2_per_dof(), r.chi2, r.points, r.value.size(), r.converged, r.starts,
                    r.seconds);
        if (r.chi2_per_dof() > 1.5)
            std::printf(
                "chi2/dof > 1: the model does not describe the data to within their errors; "
                "the errors above are statistical: multiplied by sqrt(chi2/dof) = %.3g they "
                "include the "
                "misfit (%s)\n",
                std::sqrt(r.chi2_per_dof()), r.names[0].c_str());
    }
    if (!a.output.empty()) {
        write_fit(r, a.output);
        if (!a.quiet) std::printf("wrote %s\n", a.output.c_str());
    }
    return 0;
}

std::function<int()> setup(CLI::App& app, const CliContext&) {
    auto a = std::make_shared<FitArgs>();
    std::vector<std::string> families;
    for (const NdfFamily* f : ndf_families())
        for (const Key& k : f->keys)
            if (k.name == "alpha") families.push_back(f->name);
    FitOptions& o = a->options;
    app.add_option("file", a->file, "HDF5 result file (gonio run, or gonio model)")->required();
    app.add_option("--case", o.case_name, "The case to fit (default: the only one)");
    app.add_option("--model", o.family, "NDF family of Model L1")
        ->required()
        ->check(CLI::IsMember(families));
    app.add_flag("--anisotropic", o.anisotropic, "Fit alpha_x and alpha_y, not one alpha");
    app.add_option("--orders", a->orders,
                   "Simulated orders fitted: l1 (default) or linf (the default with --with)")
        ->check(CLI::IsMember(enum_names<FitOrders>()));
    app.add_option("--with", a->with, "Multiple scattering added to Model L1 (default none)")
        ->check(CLI::IsMember(enum_names<FitWith>()));
    app.add_option("--fresnel", a->fresnel,
                   "fixed: the case's facets (default); fit: Schlick F0 per channel")
        ->check(CLI::IsMember(enum_names<FitFresnel>()));
    app.add_option("--loss", a->loss,
                   "chi2 (default: weighted by the cells' standard errors), ngan, low_l2, "
                   "low_log, bieron_l2, bieron_log")
        ->check(CLI::IsMember(enum_names<FitLoss>()));
    app.add_option("--max-theta", o.max_theta_deg,
                   "Leave out incidences and cells beyond this polar angle (degrees)")
        ->check(CLI::Range(1.0, 90.0));
    app.add_option("--reference", o.reference,
                   "gonio model files: the model fitted to (default l1, else the first)");
    app.add_option("--bootstrap", o.bootstrap,
                   "Replicas of the parametric bootstrap (default 16; 0: none)")
        ->check(CLI::Range(0, 10000));
    app.add_option("--walk-paths", o.walk_paths, "--with heitz16: paths per incidence (2^16)")
        ->check(CLI::Range(1024LL, 1LL << 30));
    app.add_option("--seed", o.seed, "Seed of the bootstrap and of heitz16's walks");
    app.add_option("-o,--output", a->output,
                   "Write the fit (FIT.toml, or FIT.json with the "
                   "residual map that `gonio report --fit` shows)");
    app.add_flag("--overwrite", a->overwrite, "Replace an existing output file");
    app.add_option("--threads", a->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(0, 4096));
    app.add_flag("-q,--quiet", a->quiet, "Print nothing on success");
    return [a] { return fit(*a); };
}
} // namespace

const Command& fit_command() {
    static const Command c{"fit", "Fit an analytic model to a case, with error bars", setup};
    return c;
}
} // namespace gonio
