#pragma once
// Surfaces whose facets follow a distribution: R19 Algorithm 1 (section 4.2, Eq. 19-22) and a
// sliced-optimal-transport matching variant, both on forward-difference Frankot-Chellappa
// (frankot_chellappa.h).
#include "heightfield/heightfield.h"
#include "heightfield/ndf/ndf.h"
#include "heightfield/surface_spec.h"

#include <functional>
#include <vector>

namespace gonio {

struct GenerationLog {
    std::vector<double>
        schwarz_mean; // mean relative Schwarz error of the assigned field, per iteration
    std::vector<double> above_threshold; // fraction of cells above the threshold, per iteration
    std::vector<double>
        ndf_distance;   // fidelity checks when stop_when_converged (every 10 iterations)
    int iterations = 0; // iterations done
    bool converged_early = false;
    double seconds = 0;           // total wall time
    double integrate_seconds = 0; // of which Frankot-Chellappa integration
    double fft_seconds = 0;       // of which the FFTs alone (fftwf_execute)
    double match_seconds = 0;     // of which the matching steps
    double schwarz_seconds = 0;   // of which the Schwarz-error log
};

using ProgressFn = std::function<void(int done, int total)>;

// Relative Schwarz (integrability) error of a gradient field at cell (x, y) [R19 Eq. 19]:
// |p(x,y) + q(x+1,y) - p(x,y+1) - q(x,y)| over the sum of the four magnitudes ("2 % of a cumulative
// d/dx and d/dy error" for the threshold 0.02).
double schwarz_error(const float* p, const float* q, int n, int x, int y);

// Generates the surface; `threads` FFTW and TBB threads (the result does not depend on it).
HeightField generate_surface(const Ndf& ndf, const SurfaceSpec& spec, int threads,
                             GenerationLog* log = nullptr, const ProgressFn& progress = {});

// The pool of R19 Algorithm 1: n*n slopes (p, q) of normals drawn from D(m) cos(theta_m), a
// deterministic function of the seed (one random stream per row).
void sample_slope_pool(const Ndf& ndf, int n, std::uint64_t seed, std::vector<float>& p,
                       std::vector<float>& q);
// The same into n*n floats each.
void sample_slope_pool(const Ndf& ndf, int n, std::uint64_t seed, float* p, float* q);

} // namespace gonio
