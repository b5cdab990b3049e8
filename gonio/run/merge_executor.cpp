// merge_parts (run.h): the part files of a sharded run, checked and assembled part by part.
#include "core/float_mode.h"
#include "gonio/run/run_assembly.h"
#include "gonio/run/unit_file.h"
#include "gonio/trace/gonioreflectometer.h"

#include <map>
#include <memory>
#include <stdexcept>

namespace gonio {

namespace {
// The config a part was made from, as it was run.
Config config_of(const UnitFileHeader& h) {
    std::vector<std::string> overrides;
    std::string line;
    for (char ch : h.overrides)
        if (ch == '\n')
            overrides.push_back(line), line.clear();
        else
            line += ch;
    Config cfg = parse_config(h.effective_toml, h.config_path);
    cfg.text = h.config_toml;
    cfg.overrides = overrides;
    return cfg;
}

// A single-incidence job's batch shards: each traced the batches b with b mod N = its index.
class BatchShards {
  public:
    void add(const std::string& part, const UnitFileHeader& h, std::vector<NumberedUnit>&& got) {
        const Shard sh = parse_shard(h.shard);
        if (count_ != 0 && sh.count != count_)
            throw std::runtime_error(part + ": shard " + sh.text() + " of a split into " +
                                     std::to_string(sh.count) + ", the others into " +
                                     std::to_string(count_));
        count_ = sh.count;
        if (got.size() != 1) throw std::runtime_error(part + ": a batch shard without its unit");
        const auto [it, fresh] = parts_.emplace(sh.index, std::make_pair(part, NumberedUnit{}));
        if (!fresh)
            throw std::runtime_error("shard " + sh.text() + " is in both " + it->second.first +
                                     " and " + part + " (a part given twice?)");
        it->second.second = std::move(got[0]);
    }
    bool empty() const { return parts_.empty(); }
    // The unit as one process tracing every batch gives it, bit for bit.
    NumberedUnit combined() {
        std::string missing;
        for (int i = 0; i < count_; ++i)
            if (!parts_.count(i)) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
        if (!missing.empty())
            throw std::runtime_error("the batch shards " + missing + " of " +
                                     std::to_string(count_) +
                                     " are in none of the parts: a part is missing");
        std::vector<TraceResult> traces;
        for (auto& [i, part] : parts_) traces.push_back(part.second.result.members.at(0));
        NumberedUnit u = std::move(parts_.begin()->second.second); // shard 0: the models
        u.result.members = {combine_batch_shards(traces)};
        return u;
    }
    const std::string& first_part() const { return parts_.begin()->second.first; }

  private:
    int count_ = 0;
    std::map<int, std::pair<std::string, NumberedUnit>> parts_; // shard index -> its part
};
} // namespace

RunResult merge_parts(const std::vector<std::string>& parts, const RunOptions& options) {
    const ResultFloatMode mode; // every entry point computes in one floating-point mode
    if (parts.empty()) throw std::runtime_error("no part files to merge");
    const RunContext context =
        run_context(options); // outlives the assembly, which holds its observer
    UnitFileHeader first;
    std::unique_ptr<RunResult> result;
    std::unique_ptr<RunAssembly> assembly;
    std::map<long long, std::string> owner; // unit -> the part that holds it
    BatchShards batches;
    for (size_t k = 0; k < parts.size(); ++k) {
        UnitFileHeader h;
        std::vector<NumberedUnit> got = read_unit_file(parts[k], &h);
        if (k == 0) {
            first = h;
            RunOptions o = options;
            o.command_line = h.command_line; // the command that made the parts
            result = std::make_unique<RunResult>(empty_result(config_of(h), o, true));
            assembly = std::make_unique<RunAssembly>(result->config, true, context.observer);
        } else if (const std::string why = h.differs_from(first); !why.empty()) {
            throw std::runtime_error(parts[k] + ": a part of another run than " + parts[0] + " (" +
                                     why + ")");
        }
        check_units(got, result->config, parts[k], h.by_batches);
        if (h.by_batches) {
            batches.add(parts[k], h, std::move(got));
            continue;
        }
        for (NumberedUnit& u : got) {
            const auto [it, fresh] = owner.emplace(u.number, parts[k]);
            if (!fresh)
                throw std::runtime_error("unit " + std::to_string(u.number) + " is in both " +
                                         it->second + " and " + parts[k] +
                                         " (a part given twice?)");
            assembly->add(u.id, std::move(u.result));
        }
    }
    if (!batches.empty()) {
        NumberedUnit u = batches.combined();
        check_unit(u, result->config, batches.first_part(), true); // (completed when added)
        if (u.result.models.size() != result->config.cases[u.id.case_index].model.models.size())
            throw std::runtime_error(batches.first_part() +
                                     ": the first batch shard's unit lacks its models");
        owner.emplace(u.number, "the batch shards");
        assembly->add(u.id, std::move(u.result));
    }
    std::string missing;
    long long count = 0;
    for (long long u = 0; u < first.units_total; ++u)
        if (!owner.count(u) && ++count <= 8)
            missing += (missing.empty() ? "" : ", ") + std::to_string(u);
    if (count > 0)
        throw std::runtime_error(std::to_string(count) + " of " +
                                 std::to_string(first.units_total) +
                                 " units are in none of the parts (" + missing +
                                 (count > 8 ? ", ..." : "") + "): a part is missing");
    result->cases = assembly->finish();
    result->execution.merged_parts = int(parts.size());
    return std::move(*result);
}

} // namespace gonio
