#include "gonio/pipeline/simulate_case.h"

#include "gonio/pipeline/surface_ensemble.h"
#include "gonio/trace/gonioreflectometer.h"
#include "gonio/trace/scene.h"

#include <cstdio>
#include <stdexcept>

namespace gonio {

namespace {
using Clock = PhaseTimes::Clock;

std::string incidence_label(const CaseConfig& c, size_t ti, size_t pi) {
    char label[160];
    std::snprintf(label, sizeof label, "%s theta_i=%g phi_i=%g", c.name.c_str(), c.theta_i_deg[ti],
                  c.phi_i_deg[pi]);
    return label;
}

HeightField make_surface(const CaseConfig& c, const SurfaceSpec& spec, const CaseRunSettings& s,
                         const CaseObserver& o, CaseResult& result) {
    const auto start = Clock::now();
    HeightField surface =
        obtain_surface(*c.ndf, spec, s.cache, s.threads, result.surface_origin, o.surface_progress);
    result.phases.add_since("surface", start);
    if (!result.surface_origin.warning.empty() && o.warn) o.warn(result.surface_origin.warning);
    return surface;
}

bool owned_here(const UnitPlan* plan, size_t ti, size_t pi) {
    return !plan || !plan->owned || plan->owned(ti, pi);
}
const UnitTraces* done_before(const UnitPlan* plan, size_t ti, size_t pi) {
    if (!plan || !plan->done) return nullptr;
    const auto it = plan->done->find({ti, pi});
    return it == plan->done->end() ? nullptr : &it->second;
}
void check_stop(const UnitPlan* plan) {
    if (plan && plan->stop_requested && plan->stop_requested()) throw Interrupted();
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

namespace {
// An ensemble of surfaces (surface.realisations >= 2): one surface and one scene in memory at a
// time, every incidence traced on each, combined with the surfaces as batches
// (surface_ensemble.h). An accuracy target is met in two stages (Stein's procedure): the first
// pass is a pilot whose error sizes the ensemble (more surfaces, and more rays on each new one
// where the rays' share would still matter), the second pass completes it and reports what it
// achieved. Iterating until the estimate falls below the target would keep the runs whose error
// was underestimated: with few surfaces' degrees of freedom, their errors read ~22 % too small.
CaseResult simulate_ensemble(const CaseConfig& c, const CaseRunSettings& s, const CaseObserver& o) {
    CaseResult result;
    result.config = &c;
    result.phases.add("ndf", c.ndf_seconds);
    result.sensor = std::make_unique<BeckersSensor>(c.sensor_cells);
    const BeckersSensor& sensor = *result.sensor;
    const auto materials = c.material.parts();
    std::vector<const Material*> parts;
    for (const auto& m : materials) parts.push_back(m.get());
    const AccuracyTarget& target = c.trace.target;
    const int first = c.surface.realisations;
    const int most = target.active() ? c.surface.max_realisations : first;
    const size_t np = c.phi_i_deg.size(), n = c.theta_i_deg.size() * np;
    struct State {
        IncidenceEnsemble ensemble;
        int wanted = 0;        // surfaces it is to have after this pass
        long long per_surface; // rays on each new surface
        bool done = false;
        std::string stop = "rays";
        double error = -1;
        int passes = 0;
    };
    std::vector<State> states(n);
    const UnitPlan* plan = s.plan;
    const bool trace_only = plan && plan->trace_only;
    std::vector<std::vector<TraceResult>> members(plan && plan->traced ? n : 0);
    std::string first_surface; // where realisation 0 is, for the file
    for (size_t i = 0; i < n; ++i) {
        State& st = states[i];
        st.wanted = first;
        st.per_surface = (std::max(1LL, c.trace.rays) + first - 1) / first;
        if (const UnitTraces* d = done_before(plan, i / np, i % np)) {
            for (const TraceResult& m : d->members) st.ensemble.add(m);
            st.done = true, st.stop = d->stop, st.passes = d->passes, st.error = d->error;
            first_surface = d->surface;
        } else if (!owned_here(plan, i / np, i % np)) {
            if (!trace_only)
                throw std::logic_error("simulate_case: an incidence neither traced nor given");
            st.done = true;
        }
    }
    std::unique_ptr<CaseModels> models;
    // Each incidence traced here, handed on whole (its surfaces and how its target ended) as soon
    // as its last pass is over: a checkpoint then holds it.
    auto hand_on = [&] {
        if (members.empty()) return;
        const auto t0 = Clock::now();
        for (size_t i = 0; i < n; ++i)
            if (states[i].done && !members[i].empty()) {
                const State& st = states[i];
                plan->traced(i / np, i % np,
                             {std::move(members[i]), st.stop, st.passes, st.error, first_surface});
                members[i].clear();
            }
        result.phases.add_since("checkpoint", t0);
    };
    const auto start = Clock::now();
    for (;;) {
        int needed = 0;
        for (const State& st : states)
            if (!st.done) needed = std::max(needed, st.wanted);
        if (needed == 0) break;
        for (int r = 0; r < needed; ++r) {
            std::vector<size_t> work;
            for (size_t i = 0; i < n; ++i) {
                const State& st = states[i];
                const int has = st.ensemble.realisations();
                if (!st.done && r >= has && r < st.wanted) work.push_back(i);
            }
            if (work.empty()) continue;
            check_stop(plan);
            const HeightField surface = make_surface(c, realisation(c.surface, r), s, o, result);
            if (r == 0) first_surface = result.surface_origin.cache_path;
            auto t = Clock::now();
            const Scene scene(surface, c.trace.backend);
            t = result.phases.add_since("scene", t);
            if (!models && r == 0 && !trace_only) { // a model fitted to a surface takes the first
                models = std::make_unique<CaseModels>(c, *c.ndf, &surface);
                result.phases.add_since("models_setup", t);
            }
            for (size_t i : work) {
                State& st = states[i];
                const size_t ti = i / np, pi = i % np;
                if (o.started)
                    o.started(incidence_label(c, ti, pi) + " surface " + std::to_string(r + 1) +
                              "/" + std::to_string(needed));
                TraceSettings ts = c.trace;
                ts.target = AccuracyTarget{}; // the ensemble's passes pursue the target
                ts.seed = s.seed;
                // Each surface is traced once per incidence, with streams of its own (surface 0:
                // the stream a single surface would use).
                const std::uint64_t base = incidence_stream(s.case_index, ti, pi);
                ts.stream = r == 0 ? base : base ^ realisation_seed(base, r);
                ts.rays = st.per_surface;
                const Vec3 wi =
                    spherical_direction(radians(c.theta_i_deg[ti]), radians(c.phi_i_deg[pi]));
                const auto t0 = Clock::now();
                TraceResult tr = trace_incidence(scene, parts, sensor, wi, ts);
                result.phases.add_since("trace", t0);
                if (!members.empty()) members[i].push_back(tr);
                st.ensemble.add(std::move(tr));
            }
        }
        const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        for (State& st : states) {
            if (st.done) continue;
            ++st.passes;
            if (!target.active()) {
                st.done = true;
                continue;
            }
            const TraceResult all = st.ensemble.combined();
            st.error = relative_error_of(all, target, sensor);
            const double goal = target.relative_error;
            // The first pass is a pilot (Stein's two-stage procedure): its error, from few
            // surfaces, only sizes the next pass. Stopping on it would keep the runs whose error
            // was underestimated and report errors too small.
            if (st.passes > 1) { // the sized pass: what it achieved is what it reports
                st.stop = st.error <= goal ? "target" : "target_not_met", st.done = true;
                continue;
            }
            if (elapsed >= target.max_seconds) {
                st.stop = "max_seconds", st.done = true;
                continue;
            }
            // Size the ensemble: both parts of the variance fall as 1 / R, so R' = R e^2 / g^2 (a
            // little past the need; at least twice the pilot, so that the pilot is at most half
            // of the final estimate). Where the rays' part would still be more than half the
            // target's variance, the new surfaces get more rays each.
            const int has = st.ensemble.realisations();
            if (has >= most) {
                st.stop = "max_realisations", st.done = true;
                continue;
            }
            const double e2 = st.error * st.error, g2 = goal * goal;
            const double rays = (1 - st.ensemble.target_share(all, target, sensor)) * e2;
            int want = std::min(most, std::max(2 * has, int(std::ceil(has * e2 / g2 * 1.05))));
            const double rays_then = rays * has / want;
            if (rays_then > 0.5 * g2)
                st.per_surface =
                    (long long)std::ceil(double(st.per_surface) * rays_then / (0.5 * g2));
            const long long left = target.max_rays - st.ensemble.rays();
            want = std::min<long long>(want, has + std::max(0LL, left) / st.per_surface);
            if (want <= has) {
                st.stop = "max_rays", st.done = true;
                continue;
            }
            st.wanted = want;
        }
        hand_on(); // the incidences this pass finished
    }
    hand_on();
    if (trace_only) return result;
    if (!models) { // every incidence came traced
        HeightField surface;
        if (c.needs_surface()) surface = make_surface(c, realisation(c.surface, 0), s, o, result);
        const auto t = Clock::now();
        models = std::make_unique<CaseModels>(c, *c.ndf, c.needs_surface() ? &surface : nullptr);
        result.phases.add_since("models_setup", t);
    }
    // The models, once per incidence, and the comparison with the ensemble.
    SimulationResult& sim = result.simulation;
    sim = SimulationResult(c.theta_i_deg, c.phi_i_deg, sensor);
    int most_surfaces = 0;
    for (const State& st : states)
        most_surfaces = std::max(most_surfaces, st.ensemble.realisations());
    sim.surface = "an ensemble of " + std::to_string(most_surfaces) + " surfaces, the first " +
                  (first_surface.empty() ? std::string("not cached") : first_surface);
    double model_seconds = 0;
    const auto t0 = Clock::now();
    for (size_t i = 0; i < n; ++i) {
        const size_t ti = i / np, pi = i % np;
        State& st = states[i];
        TraceResult all = st.ensemble.combined();
        all.stop = st.stop, all.achieved_error = target.active() ? st.error : -1;
        all.rounds = st.passes;
        const Vec3 wi = spherical_direction(radians(c.theta_i_deg[ti]), radians(c.phi_i_deg[pi]));
        const auto albedos =
            models->evaluate(wi, sensor, s.seed, incidence_stream(s.case_index, ti, pi));
        std::vector<Comparison> comparisons;
        for (size_t m = 0; m < models->results().size(); ++m)
            comparisons.push_back(
                compare_model(all, models->results()[m].compared_with == "linf", models->last(m)));
        const SurfaceShares shares = st.ensemble.shares(all, sensor);
        sim.append(all, comparisons, &shares, st.ensemble.realisations());
        if (o.finished)
            o.finished(
                {ti, pi, c.theta_i_deg[ti], c.phi_i_deg[pi], &all, &sim, &comparisons, &albedos});
    }
    result.models = models->results();
    add_model_phases(result);
    for (const ModelResult& m : result.models)
        for (double x : m.seconds.data) model_seconds += x;
    result.phases.add("compare",
                      std::chrono::duration<double>(Clock::now() - t0).count() - model_seconds);
    return result;
}
} // namespace

std::uint64_t incidence_stream(size_t case_index, size_t theta_index, size_t phi_index) {
    return (std::uint64_t(case_index) << 40) ^ (std::uint64_t(theta_index) << 20) ^
           std::uint64_t(phi_index);
}

CaseResult simulate_case(const CaseConfig& c, const CaseRunSettings& s, const CaseObserver& o) {
    if (c.surface.realisations > 1) return simulate_ensemble(c, s, o);
    CaseResult result;
    result.config = &c;
    result.phases.add("ndf", c.ndf_seconds);
    const UnitPlan* plan = s.plan;
    const bool trace_only = plan && plan->trace_only;
    // The surface and its scene only where something is traced here (or a model needs it).
    bool to_trace = false;
    std::string given_surface;
    for (size_t ti = 0; ti < c.theta_i_deg.size(); ++ti)
        for (size_t pi = 0; pi < c.phi_i_deg.size(); ++pi) {
            if (const UnitTraces* d = done_before(plan, ti, pi))
                given_surface = d->surface;
            else if (owned_here(plan, ti, pi))
                to_trace = true;
            else if (!trace_only)
                throw std::logic_error("simulate_case: an incidence neither traced nor given");
        }
    HeightField surface;
    if (to_trace || (!trace_only && c.needs_surface()))
        surface = make_surface(c, c.surface, s, o, result);
    auto t = Clock::now();
    std::unique_ptr<Scene> scene; // one surface per case: sweeps never regenerate it
    if (to_trace) scene = std::make_unique<Scene>(surface, c.trace.backend);
    t = result.phases.add_since("scene", t);
    result.sensor = std::make_unique<BeckersSensor>(c.sensor_cells);
    const auto materials = c.material.parts();
    std::vector<const Material*> parts;
    for (const auto& m : materials) parts.push_back(m.get());
    std::unique_ptr<CaseModels> models_owner;
    if (!trace_only)
        models_owner = std::make_unique<CaseModels>(
            c, *c.ndf, c.needs_surface() || to_trace ? &surface : nullptr);
    t = result.phases.add_since("models_setup", t);

    SimulationResult& sim = result.simulation;
    sim = SimulationResult(c.theta_i_deg, c.phi_i_deg, *result.sensor);
    sim.surface = !to_trace                      ? given_surface
                  : result.surface_origin.loaded ? c.surface.input
                                                 : result.surface_origin.cache_path;
    double trace_seconds = 0, incidence_seconds = 0, handed_seconds = 0;
    for (size_t ti = 0; ti < c.theta_i_deg.size(); ++ti)
        for (size_t pi = 0; pi < c.phi_i_deg.size(); ++pi) {
            const UnitTraces* given = done_before(plan, ti, pi);
            if (!given && !owned_here(plan, ti, pi)) continue;
            check_stop(plan);
            if (o.started) o.started(incidence_label(c, ti, pi));
            const auto start = Clock::now();
            const Vec3 wi =
                spherical_direction(radians(c.theta_i_deg[ti]), radians(c.phi_i_deg[pi]));
            TraceSettings st = c.trace;
            st.seed = s.seed;
            st.stream = incidence_stream(s.case_index, ti, pi);
            const TraceResult r = given ? given->members.at(0)
                                        : trace_incidence(*scene, parts, *result.sensor, wi, st);
            trace_seconds += std::chrono::duration<double>(Clock::now() - start).count();
            if (!given && plan && plan->traced) {
                const auto t0 = Clock::now(); // the checkpoint's own phase, not the comparison's
                plan->traced(ti, pi, {{r}, r.stop, 1, -1, sim.surface});
                handed_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
            }
            if (trace_only) continue;
            CaseModels& models = *models_owner;
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
    if (handed_seconds > 0) result.phases.add("checkpoint", handed_seconds);
    if (trace_only) return result;
    result.models = models_owner->results();
    result.phases.add("trace", trace_seconds);
    add_model_phases(result);
    double model_seconds = 0;
    for (const ModelResult& m : result.models)
        for (double x : m.seconds.data) model_seconds += x;
    result.phases.add("compare",
                      incidence_seconds - trace_seconds - model_seconds - handed_seconds);
    return result;
}

CaseResult evaluate_case_models(const CaseConfig& c, const CaseRunSettings& s,
                                const CaseObserver& o) {
    CaseResult result;
    result.config = &c;
    result.phases.add("ndf", c.ndf_seconds);
    HeightField surface;
    if (c.needs_surface()) surface = make_surface(c, c.surface, s, o, result);
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
