#include "heightfield/measured/gaussian_filter.h"

#include "heightfield/fftw_planner.h"

#include <algorithm>
#include <cmath>
#include <fftw3.h>
#include <memory>
#include <new>
#include <stdexcept>

namespace gonio {

namespace {
struct FftwFree {
    void operator()(double* p) const { fftw_free(p); }
};
// A plan destroyed under the planner's lock, whatever leaves the scope.
struct Plan {
    fftw_plan plan = nullptr;
    Plan(int ny, int nx, double* data, fftw_r2r_kind kind) {
        std::lock_guard<std::mutex> lock(fftw_planner());
        plan = fftw_plan_r2r_2d(ny, nx, data, data, kind, kind, FFTW_ESTIMATE);
        if (!plan) throw std::runtime_error("FFTW planning failed");
    }
    ~Plan() {
        std::lock_guard<std::mutex> lock(fftw_planner());
        fftw_destroy_plan(plan);
    }
    Plan(const Plan&) = delete;
    Plan& operator=(const Plan&) = delete;
};
} // namespace

double gaussian_transmission(double frequency, double cutoff) {
    const double alpha = std::sqrt(std::log(2.0) / M_PI);
    const double x = alpha * cutoff * frequency;
    return std::exp(-M_PI * x * x);
}

void gaussian_high_pass(std::vector<double>& z, int nx, int ny, double spacing, double cutoff) {
    std::unique_ptr<double[], FftwFree> c(fftw_alloc_real(z.size()));
    if (!c) throw std::bad_alloc();
    const Plan forward(ny, nx, c.get(), FFTW_REDFT10), backward(ny, nx, c.get(), FFTW_REDFT01);
    std::copy(z.begin(), z.end(), c.get());
    fftw_execute(forward.plan);
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
    fftw_execute(backward.plan);
    std::copy(c.get(), c.get() + z.size(), z.begin());
}

} // namespace gonio
