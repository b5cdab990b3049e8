#include "gonio/pipeline/simulate_case.h"

#include "gonio/trace/gonioreflectometer.h"
#include "gonio/trace/scene.h"

#include <cstdio>

namespace gonio {

namespace {
using Clock = PhaseTimes::Clock;

std::string incidence_label(const CaseConfig& c, size_t ti, size_t pi) {
    char label[160];
    std::snprintf(label, sizeof label, "%s theta_i=%g phi_i=%g", c.name.c_str(), c.theta_i_deg[ti],
                  c.phi_i_deg[pi]);
    return label;
}

HeightField make_surface(const CaseConfig& c, const CaseRunSettings& s, const CaseObserver& o,
                         CaseResult& result) {
    const auto start = Clock::now();
    HeightField surface = obtain_surface(*c.ndf, c.surface, s.cache, s.threads,
                                         result.surface_origin, o.surface_progress);
    result.phases.add_since("surface", start);
    if (!result.surface_origin.warning.empty() && o.warn) o.warn(result.surface_origin.warning);
    return surface;
}

// Each model's evaluation time over the sweep, as its own phase.
void add_model_phases(CaseResult& result) {
    for (const ModelResult& m : result.models) {
        double seconds = 0;
        for (double s : m.seconds.data) seconds += s;
        result.phases.add("model_" + m.name, seconds);
    }
}
} // namespace

std::uint64_t incidence_stream(size_t case_index, size_t theta_index, size_t phi_index) {
    return (std::uint64_t(case_index) << 40) ^ (std::uint64_t(theta_index) << 20) ^
           std::uint64_t(phi_index);
}

CaseResult simulate_case(const CaseConfig& c, const CaseRunSettings& s, const CaseObserver& o) {
    CaseResult result;
    result.config = &c;
    result.phases.add("ndf", c.ndf_seconds);
    const HeightField surface = make_surface(c, s, o, result);
    auto t = Clock::now();
    const Scene scene(surface); // one surface per case: sweeps never regenerate it
    t = result.phases.add_since("scene", t);
    result.sensor = std::make_unique<BeckersSensor>(c.sensor_cells);
    const auto materials = c.material.parts();
    std::vector<const Material*> parts;
    for (const auto& m : materials) parts.push_back(m.get());
    CaseModels models(c, *c.ndf, &surface);
    t = result.phases.add_since("models_setup", t);

    SimulationResult& sim = result.simulation;
    sim = SimulationResult(c.theta_i_deg, c.phi_i_deg, *result.sensor);
    sim.surface = result.surface_origin.loaded ? c.surface.input : result.surface_origin.cache_path;
    double trace_seconds = 0, incidence_seconds = 0;
    for (size_t ti = 0; ti < c.theta_i_deg.size(); ++ti)
        for (size_t pi = 0; pi < c.phi_i_deg.size(); ++pi) {
            if (o.started) o.started(incidence_label(c, ti, pi));
            const auto start = Clock::now();
            const Vec3 wi =
                spherical_direction(radians(c.theta_i_deg[ti]), radians(c.phi_i_deg[pi]));
            TraceSettings st = c.trace;
            st.seed = s.seed;
            st.stream = incidence_stream(s.case_index, ti, pi);
            const TraceResult r = trace_incidence(scene, parts, *result.sensor, wi, st);
            trace_seconds += std::chrono::duration<double>(Clock::now() - start).count();
            // The models' V-cavity paths draw from their own streams (key "VCAVITY").
            const auto albedos = models.evaluate(wi, *result.sensor, s.seed, st.stream);
            std::vector<Comparison> comparisons;
            for (size_t m = 0; m < models.results().size(); ++m)
                comparisons.push_back(
                    compare_model(r, models.results()[m].compared_with == "linf", models.last(m)));
            sim.append(r, comparisons);
            incidence_seconds += std::chrono::duration<double>(Clock::now() - start).count();
            if (o.finished)
                o.finished(
                    {ti, pi, c.theta_i_deg[ti], c.phi_i_deg[pi], &r, &sim, &comparisons, &albedos});
        }
    result.models = models.results();
    result.phases.add("trace", trace_seconds);
    add_model_phases(result);
    double model_seconds = 0;
    for (const ModelResult& m : result.models)
        for (double x : m.seconds.data) model_seconds += x;
    result.phases.add("compare", incidence_seconds - trace_seconds - model_seconds);
    return result;
}

CaseResult evaluate_case_models(const CaseConfig& c, const CaseRunSettings& s,
                                const CaseObserver& o) {
    CaseResult result;
    result.config = &c;
    result.phases.add("ndf", c.ndf_seconds);
    HeightField surface;
    if (c.needs_surface()) surface = make_surface(c, s, o, result);
    auto t = Clock::now();
    result.sensor = std::make_unique<BeckersSensor>(c.sensor_cells);
    CaseModels models(c, *c.ndf, c.needs_surface() ? &surface : nullptr);
    result.phases.add_since("models_setup", t);
    for (size_t ti = 0; ti < c.theta_i_deg.size(); ++ti)
        for (size_t pi = 0; pi < c.phi_i_deg.size(); ++pi) {
            if (o.started) o.started(incidence_label(c, ti, pi));
            const Vec3 wi =
                spherical_direction(radians(c.theta_i_deg[ti]), radians(c.phi_i_deg[pi]));
            const auto albedos =
                models.evaluate(wi, *result.sensor, s.seed, incidence_stream(s.case_index, ti, pi));
            if (o.finished)
                o.finished({ti, pi, c.theta_i_deg[ti], c.phi_i_deg[pi], nullptr, nullptr, nullptr,
                            &albedos});
        }
    result.models = models.results();
    add_model_phases(result);
    return result;
}

} // namespace gonio
