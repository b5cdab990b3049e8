#include "heightfield/measured/gaussian_filter.h"

#include "heightfield/frankot_chellappa.h"

#include <cmath>
#include <fftw3.h>
#include <mutex>

namespace gonio {

double gaussian_transmission(double frequency, double cutoff) {
    const double alpha = std::sqrt(std::log(2.0) / M_PI);
    const double x = alpha * cutoff * frequency;
    return std::exp(-M_PI * x * x);
}

void gaussian_high_pass(std::vector<double>& z, int nx, int ny, double spacing, double cutoff) {
    double* c = fftw_alloc_real(z.size());
    fftw_plan forward, backward;
    {
        std::lock_guard<std::mutex> lock(fftw_planner());
        forward = fftw_plan_r2r_2d(ny, nx, c, c, FFTW_REDFT10, FFTW_REDFT10, FFTW_ESTIMATE);
        backward = fftw_plan_r2r_2d(ny, nx, c, c, FFTW_REDFT01, FFTW_REDFT01, FFTW_ESTIMATE);
    }
    std::copy(z.begin(), z.end(), c);
    fftw_execute(forward);
    // Coefficient k of the cosine basis is frequency k / (2 n spacing) (the mirror extension's
    // period is 2n); the areal Gaussian is the product of the two axes' transmissions.
    std::vector<double> hx(static_cast<size_t>(nx)), hy(static_cast<size_t>(ny));
    for (int k = 0; k < nx; ++k)
        hx[size_t(k)] = gaussian_transmission(k / (2.0 * nx * spacing), cutoff);
    for (int k = 0; k < ny; ++k)
        hy[size_t(k)] = gaussian_transmission(k / (2.0 * ny * spacing), cutoff);
    const double norm = 1.0 / (4.0 * nx * ny); // REDFT01 after REDFT10 scales by 2n per axis
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x)
            c[size_t(y) * nx + x] *= (1.0 - hx[size_t(x)] * hy[size_t(y)]) * norm;
    fftw_execute(backward);
    std::copy(c, c + z.size(), z.begin());
    {
        std::lock_guard<std::mutex> lock(fftw_planner());
        fftw_destroy_plan(forward);
        fftw_destroy_plan(backward);
    }
    fftw_free(c);
}

} // namespace gonio
