#include "gonio/run/mpi_job.h"

#include <cstdlib>
#include <stdexcept>

#ifdef GONIO_WITH_MPI
#include <mpi.h>
#endif

namespace gonio {

namespace {
MpiJob job;
bool started = false;
bool launched_by_mpi() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(v)) return true;
    return false;
}
} // namespace

MpiJob mpi_start(int* argc, char*** argv) {
#ifdef GONIO_WITH_MPI
    if (launched_by_mpi()) {
        int provided = 0; // only the main thread calls MPI (TBB's workers never do)
        MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
        started = true;
        MPI_Comm_rank(MPI_COMM_WORLD, &job.rank);
        MPI_Comm_size(MPI_COMM_WORLD, &job.size);
    }
#else
    (void)argc, (void)argv;
    if (launched_by_mpi()) throw std::runtime_error("this gonio was built without MPI");
#endif
    return job;
}

const MpiJob& mpi_job() {
    return job;
}

void mpi_finish() {
#ifdef GONIO_WITH_MPI
    if (started) MPI_Finalize();
    started = false;
#endif
}

void mpi_abort(int code) {
#ifdef GONIO_WITH_MPI
    if (started) MPI_Abort(MPI_COMM_WORLD, code);
#endif
    std::exit(code);
}

void mpi_barrier() {
#ifdef GONIO_WITH_MPI
    if (started) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

#ifdef GONIO_WITH_MPI
namespace {
constexpr int kHeader = 1, kBody = 2;
} // namespace

void mpi_send_units(const std::vector<NumberedUnit>& units) {
    for (const NumberedUnit& u : units) {
        const long long h[4] = {u.number, (long long)u.id.case_index, (long long)u.id.theta_index,
                                (long long)u.id.phi_index};
        MPI_Send(h, 4, MPI_LONG_LONG, 0, kHeader, MPI_COMM_WORLD);
        const std::vector<char> bytes = serialise(u.result);
        if (bytes.size() >= (size_t(1) << 31)) throw std::runtime_error("a unit of 2 GB or more");
        MPI_Send(bytes.data(), int(bytes.size()), MPI_BYTE, 0, kBody, MPI_COMM_WORLD);
    }
    const long long end[4] = {-1, 0, 0, 0};
    MPI_Send(end, 4, MPI_LONG_LONG, 0, kHeader, MPI_COMM_WORLD);
}

void mpi_receive_units(const std::function<void(NumberedUnit&&)>& take) {
    for (int open = job.size - 1; open > 0;) {
        long long h[4];
        MPI_Status st;
        MPI_Recv(h, 4, MPI_LONG_LONG, MPI_ANY_SOURCE, kHeader, MPI_COMM_WORLD, &st);
        if (h[0] < 0) {
            --open;
            continue;
        }
        MPI_Status body;
        MPI_Probe(st.MPI_SOURCE, kBody, MPI_COMM_WORLD, &body);
        int count = 0;
        MPI_Get_count(&body, MPI_BYTE, &count);
        std::vector<char> bytes(static_cast<size_t>(count));
        MPI_Recv(bytes.data(), count, MPI_BYTE, st.MPI_SOURCE, kBody, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        take({h[0], {size_t(h[1]), size_t(h[2]), size_t(h[3])}, deserialise(bytes)});
    }
}
#else
void mpi_send_units(const std::vector<NumberedUnit>&) {}
void mpi_receive_units(const std::function<void(NumberedUnit&&)>&) {}
#endif

} // namespace gonio
