// run_shard (run.h): the units of one shard into a part file, for merge_parts.
#include "core/float_mode.h"
#include "core/output_files.h"
#include "gonio/io/hdf5_handles.h"
#include "gonio/run/memory_estimate.h"
#include "gonio/run/run_assembly.h"
#include "gonio/run/unit_file.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace gonio {

long long run_shard(const Config& cfg, const RunOptions& options, const Shard& shard,
                    const std::string& part) {
    const ResultFloatMode mode; // every entry point computes in one floating-point mode
    const RunContext context = run_context(options);
    check_memory(cfg, true);
    UnitFileHeader header = run_identity(cfg, options.command_line);
    header.shard = shard.text();
    // A single-incidence job has one unit: its shards share out the batches instead (each batch
    // keeps its own random streams), and the first shard alone evaluates the models.
    header.by_batches = header.units_total == 1;
    Config local = cfg;
    if (header.by_batches) {
        CaseConfig& c = local.cases[0];
        if (c.trace.target.active() || c.surface.realisations > 1)
            throw std::runtime_error("shard " + shard.text() +
                                     ": a single-incidence job shards by batches, which an "
                                     "accuracy target or a surface ensemble does not allow");
        if (shard.count > c.trace.batches)
            throw std::runtime_error("shard " + shard.text() + ": more shards than the " +
                                     std::to_string(c.trace.batches) + " batches (trace.batches)");
        c.trace.batch_shard_index = shard.index;
        c.trace.batch_shard_count = shard.count;
    }
    const UnitLayout layout(local);
    if (std::filesystem::is_directory(part)) throw std::runtime_error(part + ": is a directory");
    remove_stale_temporaries(part);
    const std::string tmp = temporary_name(part);
    long long written = 0;
    UnitFileWriter file(tmp, header, false);
    try {
        std::vector<PhaseTimes> phases(local.cases.size()); // not kept: a part holds data only
        compute_units(
            local, context,
            [&](const UnitId& id) { return header.by_batches || shard.owns(layout.number(id)); },
            !header.by_batches || shard.index == 0,
            [&](size_t ci) -> PhaseTimes& { return phases[ci]; },
            [&](const UnitId& id, UnitResult&& u) {
                file.add({layout.number(id), id, std::move(u)});
                ++written;
            });
        file.close();
        h5::write_file_checksum(tmp); // a part is written once: its every byte checksummed
    } catch (...) {
        file.discard();
        throw;
    }
    std::error_code ec;
    std::filesystem::rename(tmp, part, ec);
    if (ec) throw std::runtime_error("cannot rename " + tmp + " to " + part + ": " + ec.message());
    return written;
}

} // namespace gonio
