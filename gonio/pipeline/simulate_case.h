#pragma once
// The pipeline as one library call: everything a case needs is built once (surface, Embree scene,
// facet materials, models; the NDF was built with the config), its incidences are traced and its
// models evaluated on the same sensor cells, and a typed result comes back, with the wall time of
// every phase. `gonio run` and `gonio model` only parse arguments, call these and print.
#include "gonio/config/config.h"
#include "gonio/distributed/work_units.h"
#include "gonio/io/simulation_result.h"
#include "gonio/model/model_comparison.h"
#include "gonio/pipeline/case_models.h"
#include "gonio/pipeline/phase_times.h"
#include "gonio/trace/trace_result.h"
#include "heightfield/surface_cache.h"
#include "heightfield/surface_source.h"
#include "sensor/beckers_sensor.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace gonio {

// One incidence as it finishes, for the command line's table.
struct IncidenceReport {
    size_t theta_index = 0, phi_index = 0;
    double theta_deg = 0, phi_deg = 0;
    const TraceResult* trace = nullptr;           // null when only the models ran
    const SimulationResult* simulation = nullptr; // the case so far, this incidence included
    const std::vector<Comparison>* comparisons = nullptr;            // per model, with a trace
    const std::vector<std::vector<double>>* model_albedos = nullptr; // [model][channel]
};

struct CaseObserver {
    std::function<void(const std::string& label)> started; // an incidence begins
    std::function<void(const IncidenceReport&)> finished;
    std::function<void(const std::string& warning)> warn;
    ProgressFn surface_progress; // surface generation iterations
};

struct CaseRunSettings {
    std::uint64_t seed = 1;
    size_t case_index = 0; // mixed into every random stream
    int threads = 1;       // FFTW workers (TBB is capped by the caller)
    SurfaceCache cache{std::string()};
    // Shards, MPI ranks, checkpoints: which incidences to trace here and which came traced
    // (gonio/distributed/work_units.h). Null: trace everything.
    const UnitPlan* plan = nullptr;
};

struct CaseResult {
    const CaseConfig* config = nullptr;
    std::unique_ptr<BeckersSensor> sensor;
    SimulationResult simulation; // empty for models only
    std::vector<ModelResult> models;
    SurfaceOrigin surface_origin;
    PhaseTimes phases;
};

// Traces every incidence of `c` on its explicit surface and evaluates its models on the cells.
CaseResult simulate_case(const CaseConfig& c, const CaseRunSettings& settings,
                         const CaseObserver& observer = {});
// The models only (`gonio model`): the surface is made only for a model fitted to it.
CaseResult evaluate_case_models(const CaseConfig& c, const CaseRunSettings& settings,
                                const CaseObserver& observer = {});

// The random stream of incidence (ti, pi) of case ci: the same for the trace and the models in
// `gonio run` and `gonio model`, so V-cavity estimates agree between the two.
std::uint64_t incidence_stream(size_t case_index, size_t theta_index, size_t phi_index);

} // namespace gonio
