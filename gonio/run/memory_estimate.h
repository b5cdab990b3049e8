#pragma once
// What a run will need in memory, estimated from its config before any work: the process
// itself, each case's surface (generation's work arrays, or the traced scene), a trace in flight
// (its open batch and reductions, three order sums per batch; every batch with an accuracy
// target), a unit's completion and records on their way to the checkpoint, an ensemble's
// surface means until its last pass, and the results every case keeps until the file is
// written. Printed before a run; the result file keeps it beside the peak. Refused with the figures when it exceeds the memory the machine has
// available, instead of failing with an allocation error after minutes of work.
#include "gonio/config/config.h"

#include <string>

namespace gonio {

struct MemoryEstimate {
    double bytes = 0;    // the peak
    std::string largest; // what most of it is, for the message
};

MemoryEstimate estimate_memory(const Config& cfg, bool simulated);

// This process's peak resident memory so far (getrusage), in bytes.
double peak_memory_bytes();

// The memory the machine has available now (MemAvailable), or 0 when it cannot tell.
double available_memory_bytes();

// Throws std::runtime_error with both figures when the estimate exceeds what is available.
void check_memory(const Config& cfg, bool simulated);

} // namespace gonio
