#include "gonio/run/unit_completion.h"

#include "core/check.h"

namespace gonio {

void complete_unit(UnitResult& u, TraceResult all, const IncidenceEnsemble* ensemble,
                   const CaseConfig& c, const BeckersSensor& sensor) {
    GONIO_CHECK(!u.completed);
    if (ensemble) { // the surfaces are the batches of the ensemble's trace
        all.stop = u.stop, all.rounds = u.passes;
        all.achieved_error = c.trace.target.active() ? u.error : -1;
        u.shares = ensemble->shares(all, sensor);
        u.surfaces = ensemble->realisations();
    }
    u.comparisons.clear();
    for (size_t k = 0; k < u.models.size(); ++k)
        u.comparisons.push_back(
            compare_case_model(all, c.model.models[k].compared_with, u.models[k]));
    all.drop_order_sums();
    u.members.clear();
    u.members.push_back(std::move(all));
    u.completed = true;
}

void complete_unit(UnitResult& u, const CaseConfig& c, const BeckersSensor& sensor) {
    if (c.surface.realisations > 1) {
        IncidenceEnsemble e;
        for (TraceResult& m : u.members) e.add(std::move(m));
        complete_unit(u, e.combined(), &e, c, sensor);
    } else {
        complete_unit(u, std::move(u.members.at(0)), nullptr, c, sensor);
    }
}

} // namespace gonio
