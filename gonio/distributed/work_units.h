#pragma once
// The work of a run cut into units that can be traced anywhere and put back together exactly:
// one unit per incidence of every case, numbered in config order (case, theta_i, phi_i). A unit's
// traces (one per surface of an ensemble) depend only on the config, the seed and the unit, so
// shards, MPI ranks and resumed runs trace the same numbers a single process does, and the result
// is assembled by the one-process code path from them.
#include "gonio/trace/trace_result.h"

#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace gonio {

struct UnitTraces {
    std::vector<TraceResult> members; // one per surface (ensembles) or the one trace
    std::string stop = "rays";        // an ensemble's stop and passes, as its target decided
    int passes = 1;
    double error = -1;
    std::string surface; // where the (first) surface came from, as the result file says
};

using IncidenceKey = std::pair<size_t, size_t>; // (theta index, phi index)

// How a case's incidences are shared out and put back (null members: trace everything here).
struct UnitPlan {
    std::function<bool(size_t ti, size_t pi)> owned;          // traced here (null: all)
    const std::map<IncidenceKey, UnitTraces>* done = nullptr; // traced elsewhere or before
    std::function<void(size_t ti, size_t pi, const UnitTraces&)> traced; // as each finishes
    bool trace_only = false;              // shards and ranks: traces, no models, no result
    std::function<bool()> stop_requested; // checked between units (SIGINT)
};

// Thrown between units when stop_requested() says so.
struct Interrupted : std::runtime_error {
    Interrupted() : std::runtime_error("interrupted") {}
};

// A shard "i/N" (0 <= i < N); throws std::invalid_argument with the expected form.
struct Shard {
    int index = 0, count = 1;
    bool active() const { return count > 1; }
    bool owns(long long unit) const { return unit % count == index; }
    std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};
Shard parse_shard(const std::string& text);
// From SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT when both are set; else none.
Shard shard_from_environment();

// The bytes of a unit's traces, and back (for MPI messages); exact.
std::vector<char> serialise(const UnitTraces& u);
UnitTraces deserialise(const std::vector<char>& bytes);

} // namespace gonio
