#include "core/output_files.h"
#include "gonio/cli/cli_common.h"
#include "gonio/cli/command.h"
#include "gonio/cli/progress.h"
#include "gonio/config/config.h"
#include "heightfield/measured/surface_character.h"
#include "heightfield/surface_metrics.h"
#include "heightfield/surface_source.h"
#include "sensor/beckers_sensor.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>

namespace gonio {

namespace {

namespace fs = std::filesystem;

// Output path of a case's height map: -o as given for a single case, else with the case name.
std::string output_for(const CommonOptions& o, const Config& cfg, const CaseConfig& c) {
    if (!o.output.empty() && cfg.cases.size() == 1) return o.output;
    if (!o.output.empty()) {
        const fs::path p(o.output);
        return (p.parent_path() / (p.stem().string() + "_" + c.name + p.extension().string()))
            .string();
    }
    return fs::path(o.config).stem().string() + "_" + c.name + ".exr";
}

std::string sibling(const std::string& path, const std::string& suffix) {
    const fs::path p(path);
    return (p.parent_path() / (p.stem().string() + suffix)).string();
}

// Measured and target D(m) cos(theta_m) as images on the Lambert azimuthal equal-area disk
// (equal areas on the image are equal solid angles), and their profile over theta_m.
void write_ndf_comparison(const std::string& exr, const std::string& csv, const SurfaceMetrics& m,
                          const std::string& ndf) {
    const BeckersSensor sensor(m.ndf_bins);
    const int size = 256;
    std::vector<float> measured(size * size, 0.0f), target(size * size, 0.0f);
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            const double X = (2.0 * (i + 0.5) / size - 1.0) * std::sqrt(2.0);
            const double Y = (1.0 - 2.0 * (j + 0.5) / size) * std::sqrt(2.0);
            const double r = std::hypot(X, Y);
            if (r > std::sqrt(2.0)) continue;
            const double theta = 2.0 * std::asin(std::min(1.0, r / 2.0)), phi = std::atan2(Y, X);
            const int c = sensor.lookup(spherical_direction(theta, phi));
            const double omega = sensor.cell(c).solid_angle;
            measured[size_t(j) * size + i] = float(m.measured_mass[c] / omega);
            target[size_t(j) * size + i] = float(m.target_mass[c] / omega);
        }
    ExrAttributes a;
    a.text["gonio_content"] = "D(m) cos(theta_m) [1/sr], measured on the surface's triangles and "
                              "target, on the Lambert azimuthal equal-area disk (centre: +z)";
    a.text["gonio_ndf"] = ndf;
    write_channels_exr(exr, size, size, {"measured", "target"}, {measured, target}, a);

    std::ofstream out(csv);
    out << "# D(m) cos(theta_m) averaged over rings of " << m.ndf_bins << " equal-area cells; ndf "
        << ndf << "\n";
    out << "theta_min_deg,theta_max_deg,measured,target\n";
    for (int r = 0; r < sensor.ring_count(); ++r) {
        double mm = 0, tm = 0, omega = 0;
        for (int c = sensor.ring_first_cell(r);
             c < sensor.ring_first_cell(r) + sensor.ring_cell_count(r); ++c)
            mm += m.measured_mass[c], tm += m.target_mass[c], omega += sensor.cell(c).solid_angle;
        const SensorCell& first = sensor.cell(sensor.ring_first_cell(r));
        out << degrees(first.theta_min) << "," << degrees(first.theta_max) << "," << mm / omega
            << "," << tm / omega << "\n";
    }
    if (!out) throw std::runtime_error(csv + ": cannot write");
}

int surface(const CommonOptions& o) {
    const Config cfg = load_config(o.config, o.overrides); // throws ConfigError
    const auto limit = limit_threads(o.threads);
    const int threads = worker_threads(o.threads);
    // Refuse to replace outputs (or an input map) before any work; every file of every case
    // appears at the end, or none.
    OutputSet files(o.overwrite);
    std::map<std::string, std::string> temporary;
    for (const CaseConfig& c : cfg.cases) {
        const std::string out = output_for(o, cfg, c);
        for (const std::string& f : {out, sibling(out, "_ndf.exr"), sibling(out, "_ndf.csv"),
                                     sibling(out, "_normals.exr")}) {
            refuse_existing(f, o.overwrite);
            if (!c.surface.input.empty() && same_file(f, c.surface.input))
                throw UsageError(f + ": the output is the case's input map");
            temporary[f] = files.add(f);
        }
    }
    const SurfaceCache cache = surface_cache(o);
    for (const CaseConfig& c : cfg.cases) {
        const Ndf* ndf = c.ndf.get();
        Progress progress(c.surface.iterations, o.quiet);
        SurfaceOrigin origin;
        const HeightField surface =
            obtain_surface(*ndf, c.surface, cache, threads, origin, [&](int done, int total) {
                progress.update(done, c.name + " iteration " + std::to_string(done) + "/" +
                                          std::to_string(total));
            });
        progress.finish();
        const SurfaceMetrics m = measure_surface(surface, *ndf);
        const std::string out = output_for(o, cfg, c);
        ExrAttributes attrs = surface_attributes(*ndf, c.surface, origin.log);
        std::optional<SurfaceCharacter> character;
        if (origin.loaded) {
            attrs.text["gonio_generator"] = generator_name(c.surface);
            attrs.text["gonio_input"] = c.surface.input;
            attrs.text["gonio_edges"] = origin.edges;
            std::string steps;
            for (const std::string& line : origin.preparation)
                steps += (steps.empty() ? "" : "; ") + line;
            attrs.text["gonio_preparation"] = steps;
            // What the measured surface is, in the analytic models' terms.
            character = characterise_surface(surface);
            attrs.numbers["gonio_alpha_major"] = character->alpha_major;
            attrs.numbers["gonio_alpha_minor"] = character->alpha_minor;
            attrs.numbers["gonio_major_axis_deg"] = character->major_axis_deg;
            attrs.numbers["gonio_correlation_x"] = character->correlation_x;
            attrs.numbers["gonio_correlation_y"] = character->correlation_y;
            if (!character->unresolved) {
                for (const AnalyticFit* f : {&character->ggx, &character->beckmann}) {
                    attrs.numbers["gonio_fit_" + f->family + "_alpha"] = f->alpha_x;
                    attrs.numbers["gonio_fit_" + f->family + "_distance"] = f->distance;
                }
                for (const AnalyticFit* f : {&character->ggx_xy, &character->beckmann_xy}) {
                    attrs.numbers["gonio_fit_" + f->family + "_alpha_x"] = f->alpha_x;
                    attrs.numbers["gonio_fit_" + f->family + "_alpha_y"] = f->alpha_y;
                    attrs.numbers["gonio_fit_" + f->family + "_xy_distance"] = f->distance;
                }
            }
        }
        // The fidelity metrics travel with the surface.
        attrs.numbers["gonio_ndf_distance"] = m.ndf_distance;
        attrs.numbers["gonio_ndf_bins"] = m.ndf_bins;
        attrs.numbers["gonio_alpha_eff_x"] = m.alpha_eff_x;
        attrs.numbers["gonio_alpha_eff_y"] = m.alpha_eff_y;
        attrs.numbers["gonio_alpha_rms_x"] = m.alpha_rms_x;
        attrs.numbers["gonio_alpha_rms_y"] = m.alpha_rms_y;
        attrs.numbers["gonio_height_rms"] = m.height_rms;
        attrs.numbers["gonio_correlation_length_x"] = m.correlation_length_x;
        attrs.numbers["gonio_correlation_length_y"] = m.correlation_length_y;
        std::string histogram;
        for (double v : m.height_histogram)
            histogram += (histogram.empty() ? "" : ",") + std::to_string(v);
        attrs.text["gonio_height_histogram"] = histogram;
        attrs.numbers["gonio_height_min"] = m.height_min;
        attrs.numbers["gonio_height_max"] = m.height_max;
        write_height_exr(temporary.at(out), surface, attrs);
        write_normal_exr(temporary.at(sibling(out, "_normals.exr")), surface, attrs);
        write_ndf_comparison(temporary.at(sibling(out, "_ndf.exr")),
                             temporary.at(sibling(out, "_ndf.csv")), m, ndf->describe());
        if (!origin.warning.empty())
            std::fprintf(stderr, "gonio: warning: %s\n", origin.warning.c_str());
        if (o.quiet) continue;
        std::printf("case %s: %s, %d^2 samples, spacing %g\n", c.name.c_str(),
                    ndf->describe().c_str(), surface.n, surface.spacing);
        if (origin.loaded) {
            std::printf("  loaded %s (edges %s)\n", c.surface.input.c_str(), origin.edges.c_str());
            for (const std::string& line : origin.preparation)
                std::printf("    %s\n", line.c_str());
        } else if (origin.from_cache)
            std::printf("  reused cached surface %s (generated with %s, %d iterations)\n",
                        origin.cache_path.c_str(), generator_name(c.surface),
                        origin.log.iterations);
        else
            std::printf("  generated with %s in %.2f s (FFTs alone %.2f s), %d iterations%s%s\n",
                        generator_name(c.surface), origin.log.seconds, origin.log.fft_seconds,
                        origin.log.iterations,
                        origin.log.converged_early ? " (stopped: converged)" : "",
                        cache.enabled() ? ("; cached as " + origin.cache_path).c_str() : "");
        if (!origin.log.schwarz_mean.empty())
            std::printf("  Schwarz error (mean, R19 Eq. 19): %.4f -> %.4f; cells above %.3g: "
                        "%.1f%% -> %.1f%%\n",
                        origin.log.schwarz_mean.front(), origin.log.schwarz_mean.back(),
                        c.surface.threshold, 100 * origin.log.above_threshold.front(),
                        100 * origin.log.above_threshold.back());
        std::printf("  facet NDF vs target: total-variation distance %.4f on %d equal-area cells\n",
                    m.ndf_distance, m.ndf_bins);
        std::printf(
            "  effective alpha (median slope) x %.4f y %.4f; sqrt(2) RMS slope x %.4f y %.4f",
            m.alpha_eff_x, m.alpha_eff_y, m.alpha_rms_x, m.alpha_rms_y);
        if (m.target_alpha_x > 0)
            std::printf("; target %.4f %.4f", m.target_alpha_x, m.target_alpha_y);
        // A correlation length of half the map never fell below 1/e: it is at least that.
        const double cap = 0.5 * surface.n * surface.spacing;
        std::printf("\n  heights: RMS %.4g, range [%.4g, %.4g], correlation length x %s%.3g y "
                    "%s%.3g\n",
                    m.height_rms, m.height_min, m.height_max,
                    m.correlation_length_x >= cap ? ">= " : "", m.correlation_length_x,
                    m.correlation_length_y >= cap ? ">= " : "", m.correlation_length_y);
        if (character)
            for (const std::string& line : character->lines()) std::printf("  %s\n", line.c_str());
        std::printf("  wrote %s, %s, %s, %s\n", out.c_str(), sibling(out, "_normals.exr").c_str(),
                    sibling(out, "_ndf.exr").c_str(), sibling(out, "_ndf.csv").c_str());
    }
    files.commit();
    return 0;
}

std::function<int()> setup(CLI::App& app, const CliContext&) {
    auto o = std::make_shared<CommonOptions>();
    add_common_options(app, *o, kConfig | kSet | kOverwrite | kQuiet | kThreads | kCache);
    app.add_option("-o,--output", o->output,
                   "EXR height map (default: <config>_<case>.exr; with several cases the case "
                   "name is appended)");
    return [o] { return surface(*o); };
}
} // namespace

const Command& surface_command() {
    static const Command c{
        "surface", "Generate (or reuse from the cache) the microsurface of every case; write EXR",
        setup};
    return c;
}
} // namespace gonio
