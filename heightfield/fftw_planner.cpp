#include "heightfield/fftw_planner.h"

namespace gonio {

std::mutex& fftwf_planner() {
    static std::mutex m;
    return m;
}

std::mutex& fftw_planner() {
    static std::mutex m;
    return m;
}

} // namespace gonio
