// `gonio ndf CONFIG`: the quick look at each case's distribution before any surface is made —
// D(theta) along phi = 0 and pi/2, Smith's Lambda(theta) along both, the normalisation by
// quadrature and the albedo of Model L1 at the case's incidences. --csv writes the curves for
// scripts/plot_ndf.py.
#include "core/config_error.h"
#include "core/quadrature.h"
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/config/config.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/microfacet_model.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace gonio {

namespace {
// int D cos dw by Gauss-Legendre in theta (split in 8 pieces) and phi: a check of the
// distribution's normalisation to about 1e-6 for smooth D (the battery tests do it exactly).
double normalisation(const Ndf& ndf) {
    const GaussLegendre& g = gauss_legendre(64);
    double sum = 0;
    const int pieces = 8, phis = 128;
    for (int piece = 0; piece < pieces; ++piece) {
        const double a = 0.5 * kPi * piece / pieces, b = 0.5 * kPi * (piece + 1) / pieces;
        for (size_t i = 0; i < g.nodes.size(); ++i) {
            const double t = 0.5 * (a + b) + 0.5 * (b - a) * g.nodes[i];
            double ring = 0;
            for (int j = 0; j < phis; ++j)
                ring += ndf.D(spherical_direction(t, kTwoPi * (j + 0.5) / phis));
            sum +=
                0.5 * (b - a) * g.weights[i] * ring * (kTwoPi / phis) * std::cos(t) * std::sin(t);
        }
    }
    return sum;
}

double at(const Ndf& ndf, double theta_deg, double phi, bool lambda) {
    const Vec3 d = spherical_direction(radians(std::min(theta_deg, 89.999)), phi);
    return lambda ? ndf.lambda(d) : ndf.D(d);
}
struct NdfArgs {
    CommonOptions common;
    std::string csv; // optional: the curves at 0.5 degree steps
};

int ndf_curves(const NdfArgs& args) {
    const CommonOptions& options = args.common;
    const Config cfg = load_config(options.config, options.overrides); // throws ConfigError
    const auto limit = limit_threads(options.threads);
    std::ofstream csv;
    const std::string tmp = args.csv + ".tmp-" + std::to_string(::getpid());
    if (!args.csv.empty()) {
        csv.open(tmp);
        if (!csv) throw std::runtime_error("cannot write " + tmp);
        csv << "case,theta_deg,D_phi0,D_phi90,lambda_phi0,lambda_phi90\n";
        csv.precision(10);
    }
    for (const CaseConfig& c : cfg.cases) {
        const Ndf* ndf = c.ndf.get();
        std::printf("%s: %s\n", c.name.c_str(), ndf->describe().c_str());
        std::printf("  int D cos dw = %.6f\n", normalisation(*ndf));
        std::printf("  %8s %12s %12s %12s %12s\n", "theta", "D(phi=0)", "D(phi=90)", "Lambda(0)",
                    "Lambda(90)");
        for (double t : {0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 85.0, 89.0})
            std::printf("  %8.1f %12.6g %12.6g %12.6g %12.6g\n", t, at(*ndf, t, 0, false),
                        at(*ndf, t, 0.5 * kPi, false), at(*ndf, t, 0, true),
                        at(*ndf, t, 0.5 * kPi, true));
        if (!c.material.diffuse) {
            const BeckersSensor sensor(c.sensor_cells);
            const MicrofacetModel model(*ndf, c.material.fresnel, c.model.masking);
            for (double theta : c.theta_i_deg)
                for (double phi : c.phi_i_deg) {
                    const Vec3 wi = spherical_direction(radians(theta), radians(phi));
                    double reached = 0;
                    const std::vector<double> albedo = albedo_from_cells(
                        model_cell_energy(model, wi, sensor, c.model.quadrature, &reached),
                        model.channels());
                    std::printf("  Model L1 albedo at theta_i=%g phi_i=%g:", theta, phi);
                    for (double a : albedo) std::printf(" %.6f", a);
                    if (reached > c.model.quadrature.rel_tol) // a cell ran out of pieces
                        std::printf("  (relative error up to %.2g, not model.tolerance %g)",
                                    reached, c.model.quadrature.rel_tol);
                    std::printf("\n");
                }
        }
        if (csv)
            for (int k = 0; k <= 180; ++k) {
                const double t = 0.5 * k;
                csv << c.name << ',' << t << ',' << at(*ndf, t, 0, false) << ','
                    << at(*ndf, t, 0.5 * kPi, false) << ',' << at(*ndf, t, 0, true) << ','
                    << at(*ndf, t, 0.5 * kPi, true) << '\n';
            }
        std::fflush(stdout);
    }
    if (!args.csv.empty()) {
        csv.close();
        if (!csv) throw std::runtime_error("cannot write " + tmp);
        std::filesystem::rename(tmp, args.csv);
        std::printf("wrote %s (plot: /usr/bin/python3 scripts/plot_ndf.py %s)\n", args.csv.c_str(),
                    args.csv.c_str());
    }
    return 0;
}

std::function<int()> setup(CLI::App& app, const CliContext&) {
    auto a = std::make_shared<NdfArgs>();
    add_common_options(app, a->common, kConfig | kSet | kThreads);
    app.add_option("--csv", a->csv, "Write the curves (0.5 deg steps) to this CSV file");
    return [a] { return ndf_curves(*a); };
}
} // namespace

const Command& ndf_command() {
    static const Command c{
        "ndf", "Print each case's D and Lambda along phi = 0 and 90 deg and its Model L1 albedo",
        setup};
    return c;
}
} // namespace gonio
