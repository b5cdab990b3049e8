#pragma once
// What a run will need in memory, estimated from its config before any work: each case's
// surface (generation's work arrays, or the traced scene), the traces held until their units
// are complete (every batch's histograms, orders x cells x channels x batches doubles; an
// ensemble keeps every surface's until its last pass), and the results every case keeps until
// the file is written. Refused with the figures when it exceeds the memory the machine has
// available, instead of failing with an allocation error after minutes of work.
#include "gonio/config/config.h"

#include <string>

namespace gonio {

struct MemoryEstimate {
    double bytes = 0;    // the peak
    std::string largest; // what most of it is, for the message
};

MemoryEstimate estimate_memory(const Config& cfg, bool simulated);

// The memory the machine has available now (MemAvailable), or 0 when it cannot tell.
double available_memory_bytes();

// Throws std::runtime_error with both figures when the estimate exceeds what is available.
void check_memory(const Config& cfg, bool simulated);

} // namespace gonio
