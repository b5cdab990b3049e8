#pragma once
// The work units of one case computed here: its incidences traced on its explicit surface, or on
// each surface of an ensemble in turn (one surface and one scene in memory at a time; with an
// accuracy target, pass after pass as ensemble_plan.h sizes it), each unit's models evaluated as
// soon as its traces are final, and the unit handed on. A single surface is an ensemble of one:
// one pass, its unit handed on as soon as it is traced.
#include "gonio/config/config.h"
#include "gonio/run/phase_times.h"
#include "gonio/run/run_context.h"
#include "gonio/run/unit.h"

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace gonio {

struct CaseWork {
    const CaseConfig* config = nullptr;
    size_t case_index = 0;
    std::uint64_t seed = 1;
    std::vector<std::pair<size_t, size_t>> incidences; // (theta, phi) indices to compute here
    bool models = true; // evaluate the case's models inside its units
};

using UnitSink = std::function<void(const UnitId&, UnitResult&&)>;

// Computes `work`'s units and hands each to `sink` when complete; the phases of what is shared
// by the units (surface, scene, models_setup) are added to `phases` (a unit carries the time of
// its own traces and models). Throws Interrupted between incidences when the context says to
// stop.
void trace_case(const CaseWork& work, const RunContext& context, PhaseTimes& phases,
                const UnitSink& sink);

// The models alone at `work`'s incidences (gonio model): units without traces. A surface is made
// only for a model fitted to one.
void model_case(const CaseWork& work, const RunContext& context, PhaseTimes& phases,
                const UnitSink& sink);

// The random stream of a unit: the same for its trace and its models wherever it is computed,
// so that V-cavity estimates agree between `gonio run` and `gonio model`.
std::uint64_t incidence_stream(const UnitId& unit);

} // namespace gonio
