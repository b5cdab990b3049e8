#pragma once
// FFTW's planner is not thread-safe (only fftw_execute is): every plan is made and destroyed
// under one of these locks, since an ensemble makes its next surface while it traces.
#include <mutex>

namespace gonio {

std::mutex& fftwf_planner(); // single precision: surface generation, autocorrelation
std::mutex& fftw_planner();  // double precision: tabulated NDFs, the measured maps' filter

} // namespace gonio
