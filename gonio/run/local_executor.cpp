// run_local and run_models (run.h): every unit computed in this process.
#include "core/float_mode.h"
#include "gonio/run/run_assembly.h"
#include "gonio/run/unit_file.h"

#include <filesystem>
#include <memory>

namespace gonio {

namespace {
// The units of a checkpoint; refused (and left as it is) when it comes from another run.
std::vector<NumberedUnit> resume_from(const std::string& path, const Config& cfg,
                                      const UnitFileHeader& identity) {
    UnitFileHeader saved;
    std::vector<NumberedUnit> units = read_unit_file(path, &saved);
    if (const std::string why = saved.differs_from(identity); !why.empty())
        throw std::runtime_error(path + ": a checkpoint of another run (" + why +
                                 "); it was left as it is");
    check_units(units, cfg, path);
    return units;
}
} // namespace

RunResult run_local(const Config& cfg, const RunOptions& options, const Checkpoint& checkpoint) {
    const ResultFloatMode mode; // every entry point computes in one floating-point mode
    const RunContext context = run_context(options);
    RunResult result = empty_result(cfg, options, true);
    RunAssembly assembly(cfg, true, context.observer);
    const UnitLayout layout(cfg);
    std::unique_ptr<UnitFileWriter> file;
    std::vector<NumberedUnit> resumed;
    if (!checkpoint.path.empty()) {
        ScopedPhase t(result.phases, Phase::checkpoint);
        const UnitFileHeader identity = run_identity(cfg, options.command_line);
        if (checkpoint.resume) resumed = resume_from(checkpoint.path, cfg, identity);
        file = std::make_unique<UnitFileWriter>(checkpoint.path, identity, checkpoint.resume);
    }
    if (checkpoint.resume && context.observer.resumed)
        context.observer.resumed((long long)resumed.size(), layout.total());
    for (NumberedUnit& u : resumed) assembly.add(u.id, std::move(u.result));
    resumed.clear();
    auto sink = [&](const UnitId& id, UnitResult&& u) {
        if (file) { // first kept, then folded in (which frees its batches)
            ScopedPhase t(assembly.phases(id.case_index), Phase::checkpoint);
            file->add(layout.number(id), id, u);
        }
        assembly.add(id, std::move(u));
    };
    try {
        compute_units(
            cfg, context, [&](const UnitId& id) { return !assembly.has(id); }, true,
            [&](size_t ci) -> PhaseTimes& { return assembly.phases(ci); }, sink);
    } catch (const Interrupted&) {
        throw;      // the checkpoint holds every finished unit: `--resume` continues
    } catch (...) { // a failure leaves nothing behind: a checkpoint it created goes
        if (file && !checkpoint.resume)
            file->discard();
        else if (file)
            file->close();
        throw;
    }
    if (file) file->close();
    result.cases = assembly.finish();
    return result;
}

RunResult run_models(const Config& cfg, const RunOptions& options) {
    const ResultFloatMode mode; // every entry point computes in one floating-point mode
    const RunContext context = run_context(options);
    RunResult result = empty_result(cfg, options, false);
    RunAssembly assembly(cfg, false, context.observer);
    for (size_t ci = 0; ci < cfg.cases.size(); ++ci) {
        const CaseConfig& c = cfg.cases[ci];
        CaseWork work{&c, ci, cfg.seed, {}, true};
        for (size_t ti = 0; ti < c.theta_i_deg.size(); ++ti)
            for (size_t pi = 0; pi < c.phi_i_deg.size(); ++pi) work.incidences.emplace_back(ti, pi);
        model_case(work, context, assembly.phases(ci),
                   [&](const UnitId& id, UnitResult&& u) { assembly.add(id, std::move(u)); });
    }
    result.cases = assembly.finish();
    return result;
}

} // namespace gonio
