#pragma once
// A run under `mpirun -np K`: MPI is started only when the process was launched by an MPI
// launcher (Open MPI's or a PMI one), so the same binary runs alone without it. Ranks trace
// their share of the work units and send them to rank 0, which puts the result together by the
// one-process code path (gonio/run/mpi_executor.cpp).
#include "gonio/run/unit.h"

#include <functional>
#include <vector>

namespace gonio {

struct MpiJob {
    int rank = 0, size = 1;
    bool active() const { return size > 1; }
};

MpiJob mpi_start(int* argc, char*** argv);
const MpiJob& mpi_job();
void mpi_finish();
[[noreturn]] void mpi_abort(int code);
void mpi_barrier();
// Ranks other than 0: every unit, then an end marker, to rank 0.
void mpi_send_units(const std::vector<NumberedUnit>& units);
// Rank 0: the units of every other rank, each handed to `take` as it arrives.
void mpi_receive_units(const std::function<void(NumberedUnit&&)>& take);

} // namespace gonio
