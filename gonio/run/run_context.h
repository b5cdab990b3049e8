#pragma once
// What every executor of a run shares: the seed, the workers, the surface cache, how to report
// progress, and when to stop. The library reports through RunObserver; the command line prints
// what it hears, the tests count.
#include "gonio/config/config.h"
#include "gonio/io/simulation_result.h"
#include "gonio/model/cell_model.h"
#include "gonio/run/unit.h"
#include "heightfield/generate.h"
#include "heightfield/surface_cache.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace gonio {

// One incidence as it is put into the result.
struct IncidenceReport {
    const CaseConfig* config = nullptr;
    UnitId id;
    double theta_deg = 0, phi_deg = 0;
    const TraceResult* trace = nullptr;           // null when only the models ran
    const SimulationResult* simulation = nullptr; // the case so far, this incidence included
    const std::vector<Comparison>* comparisons = nullptr; // per model, with a trace
    const std::vector<ModelIncidence>* models = nullptr;  // per model
};

struct RunObserver {
    std::function<void(const std::string& label)> started; // work on an incidence begins
    std::function<void(const UnitId&)> unit_done;          // a unit was computed here
    std::function<void(const IncidenceReport&)> incidence; // an incidence is in the result
    std::function<void(const std::string& warning)> warn;
    std::function<void(long long done, long long total)> resumed; // units a checkpoint held
    ProgressFn surface_progress;                                  // surface generation iterations
};

struct RunContext {
    int threads = 1;                   // FFTW workers (TBB is capped by the caller)
    SurfaceCache cache{std::string()}; // disabled by default
    RunObserver observer;
    std::function<bool()> stop_requested; // checked between units (throws Interrupted)

    void check_stop() const {
        if (stop_requested && stop_requested()) throw Interrupted();
    }
};

} // namespace gonio
