// Errors that include the surface (surface.realisations >= 2): over many ensembles with distinct
// surface seeds, the spread of the ensemble means is what the reported errors say.
#include "core/special_functions.h"
#include "gonio/config/config.h"
#include "gonio/run/run.h"

#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <string>
#include <tbb/global_control.h>

using namespace gonio;

namespace {

// Schlick facets (f0 0.6): the L-infinity albedo varies too; a small surface, so that one
// surface's BSDF is far from another's.
std::string ensemble_config(int k, const std::string& extra) {
    return "seed = " + std::to_string(k + 1) + R"(
[ndf]
type = "beckmann"
alpha = 0.6
[material]
type = "schlick"
f0 = 0.6
[beam]
theta_i = 40
[sensor]
cells = 145
[model]
evaluate = false
[surface]
size = 32
iterations = 20
seed = )" + std::to_string(1000 + 7 * k) +
           "\n" + extra;
}

// Values of one quantity over the ensembles and their reported errors.
struct Spread {
    std::vector<double> value, reported;
    // The spread over the ensembles in units of the rms reported error.
    double ratio() const {
        const double n = double(value.size());
        double mean = 0, ms = 0, ss = 0;
        for (size_t k = 0; k < value.size(); ++k)
            mean += value[k] / n, ms += reported[k] * reported[k] / n;
        for (double v : value) ss += (v - mean) * (v - mean);
        return std::sqrt(ss / (n - 1) / ms);
    }
};

// The two-sided acceptance band of the ratio for n ensembles of R surfaces at level alpha: the
// squared ratio is a ratio of two variance estimates with n - 1 and n (R - 1) degrees of freedom,
// log of which is near normal with variance 2 / (n - 1) + 2 / (n (R - 1)).
double band(int n, int R, double alpha) {
    const double z = std::sqrt(2.0) * erf_quantile(1 - alpha / 2);
    return std::exp(0.5 * z * std::sqrt(2.0 / (n - 1) + 2.0 / (double(n) * (R - 1))));
}

struct EnsembleSpread {
    Spread l1, linf, cells;
    double mean_realisations = 0;
};

EnsembleSpread spread_of(int ensembles, const std::string& extra) {
    EnsembleSpread out;
    std::vector<std::vector<double>> cells, cell_errors;
    for (int k = 0; k < ensembles; ++k) {
        const Config cfg = parse_config(ensemble_config(k, extra), "ensemble.toml");
        const RunResult run = run_local(cfg, {});
        const SimulationResult& sim = run.cases[0].simulation;
        REQUIRE(sim.error_scope == ErrorScope::rays_and_surface);
        out.l1.value.push_back(sim.reflected.first_albedo.mean.at({0, 0, 0}));
        out.l1.reported.push_back(sim.reflected.first_albedo.error.at({0, 0, 0}));
        out.linf.value.push_back(sim.reflected.all_albedo.mean.at({0, 0, 0}));
        out.linf.reported.push_back(sim.reflected.all_albedo.error.at({0, 0, 0}));
        cells.push_back(sim.reflected.all.mean.block({0, 0}));
        cell_errors.push_back(sim.reflected.all.error.block({0, 0}));
        out.mean_realisations += sim.realisations.at({0, 0}) / ensembles;
    }
    // The bright cells (at least a tenth of the peak of the mean over ensembles), pooled: the
    // sum of their variances over the sum of their mean squared errors.
    std::vector<double> mean(cells[0].size(), 0.0);
    for (const auto& c : cells)
        for (size_t i = 0; i < c.size(); ++i) mean[i] += c[i] / ensembles;
    const double peak = *std::max_element(mean.begin(), mean.end());
    double ss = 0, ms = 0;
    int bright = 0;
    for (size_t i = 0; i < mean.size(); ++i) {
        if (mean[i] < 0.1 * peak) continue;
        ++bright;
        for (int k = 0; k < ensembles; ++k) {
            ss += (cells[k][i] - mean[i]) * (cells[k][i] - mean[i]) / (ensembles - 1);
            ms += cell_errors[k][i] * cell_errors[k][i] / ensembles;
        }
    }
    CHECK(bright > 10);
    out.cells.value = {std::sqrt(ss / ms)}; // already the ratio
    return out;
}

} // namespace

TEST_CASE("ensembles of 4 surfaces: the spread of 120 ensembles is their reported error") {
    // 120 ensembles make the derived band (Šidák over three quantities, 1 %) lie within
    // [0.8, 1.25].
    const int n = 120, R = 4;
    const double limit = band(n, R, 1 - std::pow(0.99, 1.0 / 3));
    CHECK(limit <= 1.25);
    const EnsembleSpread s = spread_of(n, "realisations = 4\n[trace]\nrays = 16384\nbatches = 4\n");
    const double l1 = s.l1.ratio(), linf = s.linf.ratio(), cells = s.cells.value[0];
    MESSAGE("spread / reported: L1 " << l1 << ", L-infinity " << linf << ", bright cells " << cells
                                     << " (band [" << 1 / limit << ", " << limit << "])");
    for (double ratio : {l1, linf, cells}) {
        CHECK(ratio > 1 / limit);
        CHECK(ratio < limit);
    }
}

TEST_CASE(
    "an ensemble's accuracy target adds surfaces, and its errors are the spread of 120 runs") {
    const int n = 120, R = 4;
    const double limit = band(n, R, 1 - std::pow(0.99, 1.0 / 3));
    // The L1 albedo of 32^2 surfaces varies far more between surfaces than between the rays.
    const EnsembleSpread s =
        spread_of(n, "realisations = 4\nmax_realisations = 64\n[trace]\nrays = 8192\nbatches = "
                     "4\ntarget_error = 0.004\n");
    const double l1 = s.l1.ratio(), linf = s.linf.ratio(), cells = s.cells.value[0];
    MESSAGE("target run: mean surfaces " << s.mean_realisations << "; spread / reported: L1 " << l1
                                         << ", L-infinity " << linf << ", bright cells " << cells);
    CHECK(s.mean_realisations > 8); // surfaces were added
    for (double ratio : {l1, linf, cells}) {
        CHECK(ratio > 1 / limit);
        CHECK(ratio < limit);
    }
    // Every run met its target (or said why not).
    for (double e : s.l1.reported) CHECK(e > 0);
}

TEST_CASE("an ensemble gives the same numbers with 1 and 2 threads, with and without a target") {
    for (const std::string extra :
         {"realisations = 3\n[trace]\nrays = 8192\nbatches = 4\n",
          "realisations = 3\nmax_realisations = 12\n[trace]\nrays = 4096\nbatches = 4\n"
          "target_error = 0.003\n"}) {
        const Config cfg = parse_config(ensemble_config(0, extra), "ensemble.toml");
        std::vector<std::vector<double>> runs;
        for (int threads : {1, 2}) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            RunOptions o;
            o.threads = threads;
            const RunResult run = run_local(cfg, o);
            const CaseResult& r = run.cases[0];
            std::vector<double> all = r.simulation.reflected.distribution.mean.data;
            for (const Array* a : {&r.simulation.reflected.distribution.error,
                                   &r.simulation.reflected.all_albedo.error,
                                   &r.simulation.share_linf_cells, &r.simulation.realisations})
                all.insert(all.end(), a->data.begin(), a->data.end());
            runs.push_back(all);
        }
        CHECK(runs[0] == runs[1]);
    }
}
