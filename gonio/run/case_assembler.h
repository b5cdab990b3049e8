#pragma once
// A case's result put together from its work units, whatever computed them and in whatever order
// they arrive: the one code path by which every executor (a process alone, with its checkpoint,
// MPI's rank 0, gonio merge) assembles results. Each unit is folded in as it comes (completed
// where it was traced, unit_completion.h; a batch shard's merged units completed here), so a case
// never holds more than its finished arrays and the unit at hand.
#include "gonio/config/config.h"
#include "gonio/io/model_result.h"
#include "gonio/io/simulation_result.h"
#include "gonio/run/phase_times.h"
#include "gonio/run/run_context.h"
#include "gonio/run/unit.h"
#include "sensor/beckers_sensor.h"

#include <memory>
#include <vector>

namespace gonio {

struct CaseResult {
    std::unique_ptr<BeckersSensor> sensor;
    SimulationResult simulation; // empty when only the models ran
    std::vector<ModelResult> models;
    PhaseTimes phases;
};

class CaseAssembler {
  public:
    // `simulated`: the units carry traces (gonio run), else models only (gonio model).
    CaseAssembler(const CaseConfig& c, bool simulated);
    // Folds the unit of incidence id in (its "compare" phase) and tells `observer`.
    void add(const UnitId& id, UnitResult&& unit, const RunObserver& observer = {});
    bool has(size_t theta_index, size_t phi_index) const;
    bool complete() const { return added_ == expected_; }
    // The case's phases so far (the tracer adds its own here too).
    PhaseTimes& phases() { return result_.phases; }
    // The result, once every incidence is in.
    CaseResult finish();

  private:
    const CaseConfig& c_;
    bool simulated_;
    CaseResult result_;
    std::vector<double> projected_solid_angle_; // per cell
    std::vector<bool> added_at_;
    size_t added_ = 0, expected_ = 0;
    int most_surfaces_ = 0;
    long long surface_from_ = -1; // the sweep index whose surface text the file shows
    std::string surface_;
};

} // namespace gonio
