#pragma once
// The terminal's view of a run (gonio run, gonio merge): a progress line while units are
// computed, then one row per channel of every incidence as it is put into the result: simulated
// L1 with its error, the first model of single scattering beside it (every model is in the
// file), L2+, the transmitted and lost parts.
#include "gonio/cli/progress.h"
#include "gonio/config/config.h"
#include "gonio/run/run_context.h"

namespace gonio {

class RunTable {
  public:
    // Prints the header unless quiet; `units`: how many the progress line counts to;
    // `checkpoint`: what a resumed run continues.
    RunTable(long long units, bool quiet, std::string checkpoint = "");
    RunObserver observer();
    void finish() { progress_.finish(); }

  private:
    void print(const IncidenceReport& r);
    bool quiet_;
    std::string checkpoint_;
    Progress progress_;
    long long done_ = 0;
};

} // namespace gonio
