#include "gonio/run/case_tracer.h"

#include "core/buffer_pool.h"
#include "gonio/run/case_models.h"
#include "gonio/run/ensemble_plan.h"
#include "gonio/run/surface_ensemble.h"
#include "gonio/run/unit_completion.h"
#include "gonio/trace/gonioreflectometer.h"
#include "gonio/trace/scene.h"
#include "heightfield/measured/surface_character.h"
#include "heightfield/surface_source.h"

#include <chrono>
#include <cstdio>
#include <memory>

namespace gonio {

namespace {
// A measured map in the result: the file, what was read and done to it and, for a prepared
// (third-party) map, what the surface is in the analytic models' terms.
std::string loaded_text(const std::string& input, const SurfaceOrigin& origin,
                        const HeightField& surface) {
    if (origin.preparation.empty()) return input; // an OpenEXR map read as stored
    std::string text = input;
    for (const std::string& step : origin.preparation)
        text += (step == origin.preparation.front() ? " (" : "; ") + step;
    return text + "; " + characterise_surface(surface).summary() + ")";
}
} // namespace

std::uint64_t incidence_stream(const UnitId& u) {
    return (std::uint64_t(u.case_index) << 40) ^ (std::uint64_t(u.theta_index) << 20) ^
           std::uint64_t(u.phi_index);
}

namespace {
using Clock = PhaseTimes::Clock;

Vec3 incidence_direction(const CaseConfig& c, const UnitId& id) {
    return spherical_direction(radians(c.theta_i_deg[id.theta_index]),
                               radians(c.phi_i_deg[id.phi_index]));
}

std::string incidence_label(const CaseConfig& c, const UnitId& id) {
    char text[200];
    std::snprintf(text, sizeof text, "%s theta_i=%g phi_i=%g", c.name.c_str(),
                  c.theta_i_deg[id.theta_index], c.phi_i_deg[id.phi_index]);
    return text;
}

// One incidence of the case while it is being computed.
struct Incidence {
    UnitId id;
    std::vector<TraceResult> members; // the one surface's trace
    IncidenceEnsemble ensemble;       // an ensemble's surfaces traced so far, reduced
    int traced = 0;                   // surfaces traced so far
    int wanted = 1;                   // surfaces it is to have after this pass
    long long per_surface = 0;        // rays on each new surface
    int passes = 0;
    double error = -1;
    bool done = false;
};

class CaseTracer {
  public:
    CaseTracer(const CaseWork& w, const RunContext& x, PhaseTimes& phases, const UnitSink& sink)
        : work_(w), c_(*w.config), context_(x), phases_(phases), sink_(sink),
          sensor_(c_.sensor_cells), first_(c_.surface.realisations) {
        materials_ = c_.material.parts();
        for (const auto& m : materials_) parts_.push_back(m.get());
        for (const auto& [ti, pi] : w.incidences) {
            Incidence& i = incidences_.emplace_back();
            i.id = {w.case_index, ti, pi};
            i.wanted = first_;
            i.per_surface = (std::max(1LL, c_.trace.rays) + first_ - 1) / first_;
        }
    }

    void run() {
        start_ = Clock::now();
        for (int needed = most_wanted(); needed > 0; needed = most_wanted()) {
            for (int r = 0; r < needed; ++r) trace_surface(r, needed);
            end_pass();
        }
        release_buffers(); // the next case's tallies have other sizes
    }

  private:
    int most_wanted() const {
        int needed = 0;
        for (const Incidence& i : incidences_)
            if (!i.done) needed = std::max(needed, i.wanted);
        return needed;
    }

    std::string label(const Incidence& i, int r, int needed) const {
        const std::string text = incidence_label(c_, i.id);
        if (first_ == 1) return text;
        return text + " surface " + std::to_string(r + 1) + "/" + std::to_string(needed);
    }

    // Surface r of the ensemble: made, put in a scene, and every incidence that still needs it
    // traced on it.
    void trace_surface(int r, int needed) {
        std::vector<Incidence*> work;
        for (Incidence& i : incidences_)
            if (!i.done && r >= i.traced && r < i.wanted) work.push_back(&i);
        if (work.empty()) return;
        context_.check_stop();
        SurfaceOrigin origin;
        HeightField surface;
        {
            ScopedPhase t(phases_, Phase::surface);
            surface = obtain_surface(*c_.ndf, realisation(c_.surface, r), context_.cache,
                                     context_.threads, origin, context_.observer.surface_progress);
        }
        if (!origin.warning.empty() && context_.observer.warn)
            context_.observer.warn(origin.warning);
        if (r == 0)
            surface_text_ =
                origin.loaded ? loaded_text(c_.surface.input, origin, surface) : origin.cache_path;
        std::unique_ptr<Scene> scene;
        {
            ScopedPhase t(phases_, Phase::scene);
            scene = std::make_unique<Scene>(surface, *c_.trace.backend);
        }
        if (r == 0 && work_.models && !models_) { // a model fitted to a surface takes the first
            ScopedPhase t(phases_, Phase::models_setup);
            models_ = std::make_unique<CaseModels>(c_, &surface);
        } else if (models_ && r == models_->surfaces()) { // models of the surface take them all
            ScopedPhase t(phases_, Phase::models_setup);
            models_->add_surface(surface);
        }
        for (Incidence* i : work) {
            context_.check_stop();
            if (context_.observer.started) context_.observer.started(label(*i, r, needed));
            trace_on(*scene, r, *i);
            if (first_ == 1) { // a single surface: the unit is complete
                i->passes = 1;
                finish(*i, i->members.at(0).stop);
            }
        }
    }

    void trace_on(const Scene& scene, int r, Incidence& i) {
        TraceSettings ts = c_.trace;
        ts.seed = work_.seed;
        // Each surface is traced once per incidence, with streams of its own (surface 0: the
        // stream a single surface uses). An ensemble's passes pursue its target, not each trace.
        const std::uint64_t base = incidence_stream(i.id);
        ts.stream = r == 0 ? base : base ^ realisation_seed(base, r);
        ts.rays = i.per_surface;
        if (first_ > 1) ts.target = AccuracyTarget{};
        // (Its time, and its models', are the unit's own: the assembly adds them to the phases.)
        TraceResult trace =
            trace_incidence(scene, parts_, sensor_, incidence_direction(c_, i.id), ts);
        ++i.traced;
        if (first_ > 1)
            i.ensemble.add(std::move(trace)); // its batches reduced, then dropped
        else
            i.members.push_back(std::move(trace));
    }

    // After every surface of a pass: each ensemble's target decides whether it is complete.
    void end_pass() {
        const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
        const AccuracyTarget& target = c_.trace.target;
        for (Incidence& i : incidences_) {
            if (i.done) continue;
            ++i.passes;
            EnsembleStep step;
            if (target.active()) {
                const TraceResult all = i.ensemble.combined();
                i.error = relative_error_of(all, target, sensor_);
                const EnsembleStatus status{i.passes,          i.ensemble.realisations(),
                                            i.ensemble.rays(), i.per_surface,
                                            i.error,           elapsed};
                step = plan_ensemble(target, c_.surface.max_realisations, status,
                                     [&] { return i.ensemble.target_share(all, target, sensor_); });
            }
            if (step.done) {
                finish(i, step.stop);
            } else {
                i.wanted = step.wanted;
                i.per_surface = step.per_surface;
            }
        }
    }

    // The unit is complete: its models, its comparisons with them (a batch shard's wait for
    // gonio merge), then on to the sink.
    void finish(Incidence& i, StopReason stop) {
        i.done = true;
        UnitResult u;
        u.stop = stop, u.passes = i.passes, u.error = i.error;
        u.surface = surface_text_;
        if (models_)
            u.models = models_->evaluate(incidence_direction(c_, i.id), sensor_, work_.seed,
                                         incidence_stream(i.id), i.traced);
        // The completion's time joins the compare phase after the sink, so that the phases
        // stay in the order they logically run (trace, models, compare).
        const auto completing = Clock::now();
        if (first_ > 1)
            complete_unit(u, i.ensemble.combined(), &i.ensemble, c_, sensor_);
        else if (c_.trace.batch_shard_count > 1)
            u.members = std::move(i.members);
        else
            complete_unit(u, std::move(i.members.at(0)), nullptr, c_, sensor_);
        const double completion = std::chrono::duration<double>(Clock::now() - completing).count();
        i.members.clear();
        i.ensemble = IncidenceEnsemble{};
        if (context_.observer.unit_done) context_.observer.unit_done(i.id);
        sink_(i.id, std::move(u));
        phases_.add(Phase::compare, completion);
    }

    const CaseWork& work_;
    const CaseConfig& c_;
    const RunContext& context_;
    PhaseTimes& phases_;
    const UnitSink& sink_;
    const BeckersSensor sensor_;
    const int first_; // the configured surfaces
    std::vector<std::unique_ptr<Material>> materials_;
    std::vector<const Material*> parts_;
    std::vector<Incidence> incidences_;
    std::unique_ptr<CaseModels> models_;
    std::string surface_text_;
    Clock::time_point start_;
};
} // namespace

void trace_case(const CaseWork& work, const RunContext& context, PhaseTimes& phases,
                const UnitSink& sink) {
    if (work.incidences.empty()) return;
    CaseTracer(work, context, phases, sink).run();
}

void model_case(const CaseWork& work, const RunContext& context, PhaseTimes& phases,
                const UnitSink& sink) {
    if (work.incidences.empty()) return;
    const CaseConfig& c = *work.config;
    HeightField surface;
    if (c.needs_surface()) {
        ScopedPhase t(phases, Phase::surface);
        SurfaceOrigin origin;
        surface = obtain_surface(*c.ndf, c.surface, context.cache, context.threads, origin,
                                 context.observer.surface_progress);
        if (!origin.warning.empty() && context.observer.warn) context.observer.warn(origin.warning);
    }
    ScopedPhase setup(phases, Phase::models_setup);
    const BeckersSensor sensor(c.sensor_cells);
    const CaseModels models(c, c.needs_surface() ? &surface : nullptr);
    setup.stop();
    for (const auto& [ti, pi] : work.incidences) {
        const UnitId id{work.case_index, ti, pi};
        context.check_stop();
        if (context.observer.started) context.observer.started(incidence_label(c, id));
        UnitResult u;
        u.models =
            models.evaluate(incidence_direction(c, id), sensor, work.seed, incidence_stream(id));
        if (context.observer.unit_done) context.observer.unit_done(id);
        sink(id, std::move(u));
    }
}

} // namespace gonio
