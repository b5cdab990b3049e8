#pragma once
// What the executors (run.h) share: the units of a config computed in this process, and the
// result assembled from units wherever they were computed.
#include "gonio/run/case_assembler.h"
#include "gonio/run/case_tracer.h"
#include "gonio/run/run.h"

#include <functional>
#include <vector>

namespace gonio {

// One CaseAssembler per case of the config.
class RunAssembly {
  public:
    RunAssembly(const Config& cfg, bool simulated, const RunObserver& observer);
    void add(const UnitId& id, UnitResult&& unit) {
        cases_[id.case_index].add(id, std::move(unit), observer_);
    }
    bool has(const UnitId& id) const {
        return cases_[id.case_index].has(id.theta_index, id.phi_index);
    }
    PhaseTimes& phases(size_t case_index) { return cases_[case_index].phases(); }
    std::vector<CaseResult> finish();

  private:
    const RunObserver& observer_;
    std::vector<CaseAssembler> cases_;
};

// The context of an executor's computations, from its options.
RunContext run_context(const RunOptions& options);

// A result of `cfg` with nothing in it yet: the config, the options' provenance and the phase
// "config".
RunResult empty_result(const Config& cfg, const RunOptions& options, bool simulated);

// Computes here the units for which here(id) holds, case by case (trace_case), and hands each to
// `sink`; the cases' phases go to phases(case_index).
void compute_units(const Config& cfg, const RunContext& context,
                   const std::function<bool(const UnitId&)>& here, bool models,
                   const std::function<PhaseTimes&(size_t)>& phases, const UnitSink& sink);

} // namespace gonio
