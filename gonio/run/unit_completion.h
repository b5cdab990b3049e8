#pragma once
// A unit made final: its traces (one per surface) become the incidence's one trace, compared with
// the case's models, and what only those comparisons needed (the batches' order sums, B maps
// each) reduced to their errors. Done where the unit is computed, so that checkpoints, part files
// and MPI messages carry answers and not batches; a batch shard's units are completed when
// gonio merge has put their batches together.
#include "gonio/config/config.h"
#include "gonio/run/surface_ensemble.h"
#include "gonio/run/unit.h"
#include "sensor/beckers_sensor.h"

namespace gonio {

// `all`: the one surface's trace or an ensemble's combined trace (`ensemble` then holds its
// surfaces). The unit's stop, passes and error say how its passes ended.
void complete_unit(UnitResult& u, TraceResult all, const IncidenceEnsemble* ensemble,
                   const CaseConfig& c, const BeckersSensor& sensor);

// The same from the unit's own members (a batch shard's merged unit).
void complete_unit(UnitResult& u, const CaseConfig& c, const BeckersSensor& sensor);

} // namespace gonio
