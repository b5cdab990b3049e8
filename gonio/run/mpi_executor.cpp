// run_mpi (run.h): under mpirun, every rank computes its share of the units and rank 0
// assembles the result.
#include "core/float_mode.h"
#include "gonio/run/memory_estimate.h"
#include "gonio/run/mpi_job.h"
#include "gonio/run/run_assembly.h"
#include "gonio/run/unit_file.h"
#include "heightfield/surface_source.h"

#include <stdexcept>

namespace gonio {

std::optional<RunResult> run_mpi(const Config& cfg, const RunOptions& options) {
    const ResultFloatMode mode; // every entry point computes in one floating-point mode
    const MpiJob& job = mpi_job();
    if (!options.cache.enabled())
        throw std::runtime_error("the ranks of an MPI job share their surfaces through the "
                                 "cache, which is disabled");
    const RunContext context = run_context(options);
    check_memory(cfg, true);
    // Every surface made once, the k-th (case, realisation) by rank k mod K, and shared through
    // the cache: the ranks then load what they trace.
    long long k = 0;
    for (const CaseConfig& c : cfg.cases)
        for (int r = 0; r < c.surface.realisations; ++r)
            if (k++ % job.size == job.rank) {
                SurfaceOrigin origin;
                obtain_surface(*c.ndf, realisation(c.surface, r), context.cache, context.threads,
                               origin);
            }
    mpi_barrier();
    const UnitLayout layout(cfg);
    const Shard share{job.rank, job.size}; // this rank's units
    auto mine = [&](const UnitId& id) { return share.owns(layout.number(id)); };
    if (job.rank != 0) {
        std::vector<NumberedUnit> units;
        std::vector<PhaseTimes> phases(cfg.cases.size());
        compute_units(
            cfg, context, mine, true, [&](size_t ci) -> PhaseTimes& { return phases[ci]; },
            [&](const UnitId& id, UnitResult&& u) {
                units.push_back({layout.number(id), id, std::move(u)});
            });
        mpi_send_units(units);
        return std::nullopt;
    }
    RunResult result = empty_result(cfg, options, true);
    result.execution.ranks = job.size;
    RunAssembly assembly(cfg, true, context.observer);
    compute_units(
        cfg, context, mine, true, [&](size_t ci) -> PhaseTimes& { return assembly.phases(ci); },
        [&](const UnitId& id, UnitResult&& u) { assembly.add(id, std::move(u)); });
    // The other ranks' units, checked and folded in one at a time as they arrive.
    mpi_receive_units([&](NumberedUnit&& u) {
        check_unit(u, cfg, "a message from another rank");
        assembly.add(u.id, std::move(u.result));
    });
    result.cases = assembly.finish();
    return result;
}

} // namespace gonio
