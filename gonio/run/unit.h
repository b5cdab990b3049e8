#pragma once
// The work of a run cut into units that can be computed anywhere and put back together exactly:
// one unit per incidence of every case, numbered in config order (case, theta_i, phi_i) by
// UnitLayout, the one place that numbers them. A unit's result, its traces (one per surface of an
// ensemble) and its models at that incidence, depends only on the config, the seed and the unit,
// so shards, MPI ranks and resumed runs compute the same bits a single process does, and every
// executor assembles the result from units by one code path (case_assembler.h).
#include "gonio/config/config.h"
#include "gonio/model/cell_model.h"
#include "gonio/model/model_comparison.h"
#include "gonio/trace/trace_result.h"

#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

struct UnitId {
    size_t case_index = 0, theta_index = 0, phi_index = 0;
};

class UnitLayout {
  public:
    explicit UnitLayout(const Config& cfg);
    long long total() const { return first_.back(); }
    long long number(const UnitId& u) const;
    UnitId unit(long long number) const;
    long long first(size_t case_index) const { return first_[case_index]; }
    long long count(size_t case_index) const { return first_[case_index + 1] - first_[case_index]; }
    size_t cases() const { return phi_count_.size(); }

  private:
    std::vector<long long> first_; // per case, then the total
    std::vector<size_t> phi_count_;
};

struct UnitResult {
    std::vector<TraceResult> members; // one per surface (ensembles) or the one trace
    // How an ensemble's passes ended (its target decided; a single surface's trace says itself).
    StopReason stop = StopReason::rays;
    int passes = 1;
    double error = -1;
    std::string surface; // where the (first) surface came from, as the result file says
    // Every model of the case at this incidence, in the case's order (empty in the batch shards
    // of a single-incidence job but the first: one is enough).
    std::vector<ModelIncidence> models;
    // Completed where it was computed (unit_completion.h; every unit but a batch shard's):
    // members then holds one trace, the ensemble's or the surface's, with its order sums reduced
    // to their errors, and the comparisons with the models and the surfaces' shares are made.
    bool completed = false;
    int surfaces = 1;
    SurfaceShares shares;                // ensembles
    std::vector<Comparison> comparisons; // per model, in the case's order
};

// A unit with its number and place, as part files, checkpoints and MPI messages carry it.
struct NumberedUnit {
    long long number = 0;
    UnitId id;
    UnitResult result;
};

// Thrown between units when the run's stop predicate says so (SIGINT).
struct Interrupted : std::runtime_error {
    Interrupted() : std::runtime_error("interrupted") {}
};

// A shard "i/N" (0 <= i < N): the units whose number is i mod N.
struct Shard {
    int index = 0, count = 1;
    bool active() const { return count > 1; }
    bool owns(long long unit) const { return unit % count == index; }
    std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};
// Throws std::invalid_argument with the expected form.
Shard parse_shard(const std::string& text);
// From SLURM_ARRAY_TASK_ID (less SLURM_ARRAY_TASK_MIN) and SLURM_ARRAY_TASK_COUNT when both are
// set; else none.
Shard shard_from_environment();

// The bytes of a unit's result, and back (part files, checkpoints, MPI messages); exact.
std::vector<char> serialise(const UnitResult& u);
UnitResult deserialise(const std::vector<char>& bytes);

} // namespace gonio
