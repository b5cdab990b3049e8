#pragma once
// One floating-point environment for every thread that computes a result: flush-to-zero and
// denormals-are-zero on (x86-64; elsewhere nothing changes). Embree turns them on in the threads
// that build or trace its scenes (its performance recommendation) and leaves them on, so a TBB
// worker's mode used to depend on whether it had run Embree before: a model evaluated after
// tracing gave 0 where the same model evaluated in a process that traced nothing (gonio merge, a
// rank that only gathers, gonio model) gave ~1e-305. Now every parallel loop of the library
// (core/parallel.h) sets the mode in each task, and every entry point in its calling thread, so
// results are the same bits whatever the process, rank, thread or backend.
namespace gonio {

// Sets the mode in the calling thread (main does, before anything else).
void use_result_float_mode();

// Whether the calling thread is in the mode (tests).
bool in_result_float_mode();

// The mode for as long as it lives, then the calling thread's own again: the library's entry
// points and parallel tasks use it, so a caller's thread (a Python interpreter's, say) keeps its
// mode outside gonio's calls.
class ResultFloatMode {
  public:
    ResultFloatMode();
    ~ResultFloatMode();
    ResultFloatMode(const ResultFloatMode&) = delete;
    ResultFloatMode& operator=(const ResultFloatMode&) = delete;

  private:
    unsigned saved_ = 0;
};

} // namespace gonio
