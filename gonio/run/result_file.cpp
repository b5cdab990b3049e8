// write_result (run.h): a run's result as the HDF5 result file (gonio/io/result_writer.h).
#include "gonio/io/result_writer.h"
#include "gonio/run/memory_estimate.h"
#include "gonio/run/run.h"

namespace gonio {

namespace {
void write_all(const RunResult& r, ResultWriter& writer) {
    auto t = PhaseTimes::Clock::now();
    PhaseTimes run = r.phases;
    writer.write_run(r.config, r.command_line);
    if (r.simulated) // how the traces were spread (gonio model traces nothing)
        writer.write_execution(r.execution.ranks, r.execution.threads_per_rank,
                               r.execution.merged_parts);
    t = run.add_since(Phase::writing, t);
    for (size_t ci = 0; ci < r.cases.size(); ++ci) {
        const CaseConfig& c = r.config.cases[ci];
        const CaseResult& cr = r.cases[ci];
        if (r.simulated)
            writer.write_simulation_case(c, *cr.sensor, c.ndf->describe(), cr.simulation,
                                         cr.models);
        else
            writer.write_model_case(c, *cr.sensor, c.ndf->describe(), cr.models);
        PhaseTimes phases = cr.phases;
        phases.add_since(Phase::writing, t);
        writer.write_timings(c.name, phases.phases());
        run.merge(phases);
        t = PhaseTimes::Clock::now();
    }
    // The estimate against what this process used at its peak (the result's arrays included).
    if (r.execution.memory_estimate_bytes > 0)
        writer.write_memory(r.execution.memory_estimate_bytes, peak_memory_bytes());
    run.add_since(Phase::writing, t);
    run.add(Phase::wall,
            std::chrono::duration<double>(PhaseTimes::Clock::now() - r.started).count());
    writer.write_timings("", run.phases());
    writer.commit();
}
} // namespace

void write_result(const RunResult& r, ResultWriter& writer) {
    try {
        write_all(r, writer);
    } catch (const std::exception& e) { // the writer's errors name what failed, this the file
        throw std::runtime_error(writer.path() + ": " + e.what());
    }
}

void write_result_file(const RunResult& r, const std::string& path, bool overwrite) {
    ResultWriter writer(path, overwrite);
    write_result(r, writer);
}

} // namespace gonio
