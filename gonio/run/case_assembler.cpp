#include "gonio/run/case_assembler.h"

#include "core/buffer_pool.h"
#include "core/check.h"
#include "gonio/model/model_comparison.h"
#include "gonio/run/unit_completion.h"

#include <algorithm>
#include <cstdio>

namespace gonio {

CaseAssembler::CaseAssembler(const CaseConfig& c, bool simulated) : c_(c), simulated_(simulated) {
    result_.sensor = std::make_unique<BeckersSensor>(c.sensor_cells);
    projected_solid_angle_ = result_.sensor->projected_solid_angles();
    result_.phases.add(Phase::ndf, c.ndf_seconds);
    const size_t nt = c.theta_i_deg.size(), np = c.phi_i_deg.size();
    expected_ = nt * np;
    added_at_.assign(expected_, false);
    if (simulated)
        result_.simulation = SimulationResult(c.theta_i_deg, c.phi_i_deg, *result_.sensor);
    for (const ModelChoice& m : c.model.models) {
        ModelResult& r = result_.models.emplace_back();
        r.name = m.name;
        r.compared_with = m.compared_with;
        r.description = m.description;
    }
}

bool CaseAssembler::has(size_t t, size_t p) const {
    return added_at_[t * c_.phi_i_deg.size() + p];
}

void CaseAssembler::add(const UnitId& id, UnitResult&& u, const RunObserver& observer) {
    ScopedPhase timer(result_.phases, Phase::compare);
    const size_t t = id.theta_index, p = id.phi_index, at = t * c_.phi_i_deg.size() + p;
    GONIO_CHECK(t < c_.theta_i_deg.size() && p < c_.phi_i_deg.size() && !added_at_[at]);
    GONIO_CHECK(u.models.size() == result_.models.size());
    GONIO_CHECK(u.members.empty() != simulated_);
    const std::vector<double>& psa = projected_solid_angle_;
    if (added_ == 0)
        for (size_t k = 0; k < u.models.size(); ++k)
            result_.models[k].allocate(c_.theta_i_deg.size(), c_.phi_i_deg.size(), psa.size(),
                                       size_t(c_.channels()), u.models[k]);
    // The unit's own times: its traces', then its models'.
    for (const TraceResult& m : u.members) result_.phases.add(Phase::trace, m.seconds);
    for (size_t k = 0; k < u.models.size(); ++k) {
        const double reached = u.models[k].relative_tolerance;
        if (!u.models[k].monte_carlo() && reached > c_.model.quadrature.rel_tol && observer.warn) {
            char text[320];
            std::snprintf(text, sizeof text,
                          "%s: model_%s at theta_i=%g phi_i=%g: the quadrature ran out of pieces "
                          "at a relative error of %.2g (model.tolerance %g); a larger "
                          "model.tolerance gives that bound in less time",
                          c_.name.c_str(), result_.models[k].name.c_str(), c_.theta_i_deg[t],
                          c_.phi_i_deg[p], reached, c_.model.quadrature.rel_tol);
            observer.warn(text);
        }
        result_.models[k].put(t, p, u.models[k], psa);
        result_.phases.add_model(result_.models[k].name, u.models[k].seconds);
    }
    if (surface_from_ < 0 || (long long)at < surface_from_)
        surface_from_ = at, surface_ = u.surface;

    TraceResult all;
    std::vector<Comparison> comparisons;
    if (simulated_) {
        if (!u.completed) complete_unit(u, c_, *result_.sensor); // a merged batch shard's
        all = std::move(u.members.at(0));
        comparisons = std::move(u.comparisons);
        const bool ensemble = c_.surface.realisations > 1;
        most_surfaces_ = std::max(most_surfaces_, u.surfaces);
        result_.simulation.put(t, p, all, comparisons, ensemble ? &u.shares : nullptr, u.surfaces);
        for (auto map : {&TraceResult::energy, &TraceResult::energy_stderr,
                         &TraceResult::transmitted, &TraceResult::transmitted_stderr})
            give_back(std::move(all.*map)); // copied into the result: for the next trace
    }
    added_at_[at] = true;
    ++added_;
    timer.stop();
    if (observer.incidence)
        observer.incidence({&c_, id, c_.theta_i_deg[t], c_.phi_i_deg[p],
                            simulated_ ? &all : nullptr, simulated_ ? &result_.simulation : nullptr,
                            simulated_ ? &comparisons : nullptr, &u.models});
}

CaseResult CaseAssembler::finish() {
    GONIO_CHECK_MSG(complete(), "case " + c_.name + ": " + std::to_string(expected_ - added_) +
                                    " incidences missing");
    SimulationResult& sim = result_.simulation;
    if (simulated_)
        sim.surface = c_.surface.realisations == 1
                          ? surface_
                          : "an ensemble of " + std::to_string(most_surfaces_) +
                                " surfaces, the first " +
                                (surface_.empty() ? std::string("not cached") : surface_);
    return std::move(result_);
}

} // namespace gonio
