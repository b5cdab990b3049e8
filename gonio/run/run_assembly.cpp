#include "gonio/run/run_assembly.h"

#include "gonio/run/memory_estimate.h"

#include <algorithm>

namespace gonio {

RunAssembly::RunAssembly(const Config& cfg, bool simulated, const RunObserver& observer)
    : observer_(observer) {
    cases_.reserve(cfg.cases.size());
    for (const CaseConfig& c : cfg.cases) cases_.emplace_back(c, simulated);
}

std::vector<CaseResult> RunAssembly::finish() {
    std::vector<CaseResult> out;
    for (CaseAssembler& c : cases_) out.push_back(c.finish());
    return out;
}

RunContext run_context(const RunOptions& o) {
    RunContext x;
    x.threads = worker_threads(o.threads);
    x.cache = o.cache;
    x.observer = o.observer;
    x.stop_requested = o.stop_requested;
    return x;
}

RunResult empty_result(const Config& cfg, const RunOptions& o, bool simulated) {
    check_memory(cfg, simulated); // before any work: refused with the figures
    RunResult r;
    r.execution.memory_estimate_bytes = estimate_memory(cfg, simulated).bytes;
    r.config = cfg;
    r.simulated = simulated;
    r.command_line = o.command_line;
    r.started = o.started;
    r.execution.threads_per_rank = worker_threads(o.threads);
    double ndf_seconds = 0;
    for (const CaseConfig& c : cfg.cases) ndf_seconds += c.ndf_seconds;
    r.phases.add(Phase::config, std::max(0.0, o.config_seconds - ndf_seconds));
    return r;
}

void compute_units(const Config& cfg, const RunContext& context,
                   const std::function<bool(const UnitId&)>& here, bool models,
                   const std::function<PhaseTimes&(size_t)>& phases, const UnitSink& sink) {
    for (size_t ci = 0; ci < cfg.cases.size(); ++ci) {
        const CaseConfig& c = cfg.cases[ci];
        CaseWork work{&c, ci, cfg.seed, {}, models};
        for (size_t ti = 0; ti < c.theta_i_deg.size(); ++ti)
            for (size_t pi = 0; pi < c.phi_i_deg.size(); ++pi)
                if (here({ci, ti, pi})) work.incidences.emplace_back(ti, pi);
        trace_case(work, context, phases(ci), sink);
    }
}

} // namespace gonio
