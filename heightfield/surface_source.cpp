#include "heightfield/surface_source.h"

#include "gonio_version.h"
#include "heightfield/measured/map_preparation.h"
#include "heightfield/measured/measured_map.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {
std::string join(const std::vector<double>& v) {
    std::ostringstream o;
    o.precision(17);
    for (size_t k = 0; k < v.size(); ++k) o << (k ? "," : "") << v[k];
    return o.str();
}
std::vector<double> split(const std::string& s) {
    std::vector<double> v;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) v.push_back(std::stod(item));
    return v;
}
} // namespace

double seam_ratio(const HeightField& s) {
    double seam = 0, inner = 0;
    for (int k = 0; k < s.n; ++k) {
        seam += std::abs(double(s.at(0, k)) - s.at(s.n - 1, k)) +
                std::abs(double(s.at(k, 0)) - s.at(k, s.n - 1));
        inner +=
            std::abs(double(s.at(1, k)) - s.at(0, k)) + std::abs(double(s.at(k, 1)) - s.at(k, 0));
    }
    return inner > 0 ? seam / inner : (seam > 0 ? 1e9 : 1.0);
}

HeightField mirror_tile(const HeightField& s) {
    HeightField out(2 * s.n, s.spacing);
    for (int y = 0; y < 2 * s.n; ++y)
        for (int x = 0; x < 2 * s.n; ++x) {
            const int sx = x < s.n ? x : 2 * s.n - 1 - x, sy = y < s.n ? y : 2 * s.n - 1 - y;
            out.h[size_t(y) * out.n + x] = s.h[size_t(sy) * s.n + sx];
        }
    return out;
}

ExrAttributes surface_attributes(const Ndf& ndf, const SurfaceSpec& spec,
                                 const GenerationLog& log) {
    ExrAttributes a;
    a.text["gonio_identity"] = surface_identity(ndf, spec);
    a.text["gonio_ndf"] = ndf.describe();
    a.text["gonio_generator"] = generator_name(spec);
    a.text["gonio_constraint"] = name_of(spec.constraint);
    a.text["gonio_seed"] = std::to_string(spec.seed);
    a.text["gonio_version"] = std::string(kVersion) + " (git " + kGitHash + ")";
    a.text["gonio_schwarz_mean"] = join(log.schwarz_mean);
    a.text["gonio_above_threshold"] = join(log.above_threshold);
    a.numbers["gonio_iterations"] = log.iterations;
    a.numbers["gonio_threshold"] = spec.threshold;
    a.numbers["gonio_generation_seconds"] = log.seconds;
    a.numbers["gonio_fft_seconds"] = log.fft_seconds;
    return a;
}

HeightField read_input_map(const SurfaceSpec& spec, std::vector<std::string>& report) {
    const MeasuredFormat& format = measured_format_of(spec.input);
    const bool exr = &format == &exr_map_format();
    // OpenEXR maps (gonio's own among them) are read exactly as stored unless asked otherwise.
    if (exr && !spec.prepare_asked) return read_height_exr(spec.input);
    MeasuredMap map =
        format.read(spec.input, {spec.input_spacing, spec.input_unit, spec.input_checksums});
    map.format = format.name;
    MapPreparation p;
    p.level = spec.level == "auto" ? (exr ? Levelling::none : Levelling::plane)
                                   : enum_named<Levelling>(spec.level);
    p.spikes = spec.spikes >= 0 ? spec.spikes : exr ? 0.0 : MapPreparation{}.spikes;
    p.max_missing = spec.max_missing;
    p.high_pass = spec.high_pass;
    PreparedMap prepared = prepare_measured_map(map, p, spec.input);
    char text[256];
    std::snprintf(text, sizeof text, "read: %s, %d x %d points, spacing %.6g x %.6g %s (%s)",
                  format.name, map.nx, map.ny, map.dx, map.dy,
                  map.unit.empty() ? "(unitless)" : map.unit.c_str(), map.note.c_str());
    report.push_back(text);
    std::snprintf(text, sizeof text, "missing: %.3g %% of the points",
                  100 * prepared.missing_share);
    report.push_back(text);
    report.insert(report.end(), prepared.report.begin(), prepared.report.end());
    if (const std::string why = height_map_problem(prepared.surface); !why.empty())
        throw std::runtime_error(spec.input + ": " + why);
    return std::move(prepared.surface);
}

HeightField obtain_surface(const Ndf& ndf, const SurfaceSpec& spec, const SurfaceCache& cache,
                           int threads, SurfaceOrigin& origin, const ProgressFn& progress) {
    origin = SurfaceOrigin{};
    if (!spec.input.empty()) {
        HeightField s = read_input_map(spec, origin.preparation);
        origin.loaded = true;
        const double ratio = seam_ratio(s);
        if (ratio > 3.0) {
            std::ostringstream w;
            w.precision(3);
            w << spec.input << " is not periodic (its edges jump " << ratio
              << " times the mean step); edges = \"" << name_of(spec.edges) << "\"";
            origin.warning = w.str();
        }
        if (spec.edges == Edges::mirror) {
            origin.edges = "mirror: tiled with its mirror images into a periodic " +
                           std::to_string(2 * s.n) + "^2 map";
            return mirror_tile(s);
        }
        origin.edges = "periodic: used as it is (any seam at the edges is kept)";
        return s;
    }
    const std::string key = surface_cache_key(ndf, spec);
    const std::string identity = surface_identity(ndf, spec);
    if (cache.enabled()) origin.cache_path = cache.path(key);
    ExrAttributes stored;
    if (auto cached = cache.load(key, identity, &stored)) {
        origin.from_cache = true;
        origin.log.schwarz_mean = split(stored.text["gonio_schwarz_mean"]);
        origin.log.above_threshold = split(stored.text["gonio_above_threshold"]);
        origin.log.iterations = int(stored.numbers["gonio_iterations"]);
        origin.log.seconds = stored.numbers["gonio_generation_seconds"];
        origin.log.fft_seconds = stored.numbers["gonio_fft_seconds"];
        return *cached;
    }
    HeightField s = generate_surface(ndf, spec, threads, &origin.log, progress);
    origin.generated = true;
    cache.store(key, s, surface_attributes(ndf, spec, origin.log));
    return s;
}

} // namespace gonio
