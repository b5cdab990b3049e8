#include "heightfield/frankot_chellappa.h"

#include "core/math.h"
#include "core/parallel.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace gonio {

namespace {
// FFTW runs its parallel loops on TBB's workers (fftw_threads_set_callback, FFTW >= 3.3.9), so
// that FFTW's own thread pool and TBB's do not compete for the same cores.
void tbb_parallel_loop(void* (*work)(char*), char* jobdata, size_t elsize, int njobs, void*) {
    parallel_for(0, njobs, [&](int j) { work(jobdata + elsize * size_t(j)); });
}
} // namespace


void init_fftw_threads() {
    static std::once_flag once;
    std::call_once(once, [] {
        fftwf_init_threads();
        fftwf_threads_set_callback(tbb_parallel_loop, nullptr);
    });
}

FrankotChellappa::FrankotChellappa(int n, int threads) : n_(n) {
    if (n < 2) throw std::invalid_argument("FrankotChellappa: size must be >= 2");
    init_fftw_threads();
    const size_t real_count = size_t(n) * n, spec_count = size_t(n) * (n / 2 + 1);
    real_ = fftwf_alloc_real(real_count);
    real_q_ = fftwf_alloc_real(real_count);
    heights_ = fftwf_alloc_real(real_count);
    spec_p_ = fftwf_alloc_complex(spec_count);
    spec_q_ = fftwf_alloc_complex(spec_count);
    if (!real_ || !real_q_ || !heights_ || !spec_p_ || !spec_q_) throw std::bad_alloc();
    // The planner is not thread-safe; plans are made here, once.
    std::lock_guard<std::mutex> lock(fftwf_planner());
    fftwf_plan_with_nthreads(std::max(1, threads));
    forward_p_ = fftwf_plan_dft_r2c_2d(n, n, real_, spec_p_, FFTW_ESTIMATE);
    forward_q_ = fftwf_plan_dft_r2c_2d(n, n, real_q_, spec_q_, FFTW_ESTIMATE);
    backward_ = fftwf_plan_dft_c2r_2d(n, n, spec_p_, heights_, FFTW_ESTIMATE);
    if (!forward_p_ || !forward_q_ || !backward_) throw std::runtime_error("FFTW planning failed");
    // Discrete derivative factors: row index v (y, all n), column index u (x, n/2 + 1).
    dx_re_.resize(n / 2 + 1), dx_im_.resize(n / 2 + 1), dy_re_.resize(n), dy_im_.resize(n);
    for (int u = 0; u <= n / 2; ++u) {
        dx_re_[u] = float(std::cos(kTwoPi * u / n) - 1.0);
        dx_im_[u] = float(std::sin(kTwoPi * u / n));
    }
    for (int v = 0; v < n; ++v) {
        dy_re_[v] = float(std::cos(kTwoPi * v / n) - 1.0);
        dy_im_[v] = float(std::sin(kTwoPi * v / n));
    }
    set_metric(1.0, 1.0);
}

void FrankotChellappa::set_metric(double wx, double wy) {
    // The least-squares weights 1 / (wx |a|^2 + wy |b|^2), with the inverse transform's 1/n^2; the
    // mean height (u = v = 0) is free: zero.
    const int n = n_, w = n / 2 + 1;
    wx_ = float(wx), wy_ = float(wy);
    inv_denom_.resize(size_t(n) * w);
    for (int v = 0; v < n; ++v)
        for (int u = 0; u < w; ++u) {
            const double d = wx * (double(dx_re_[u]) * dx_re_[u] + double(dx_im_[u]) * dx_im_[u]) +
                             wy * (double(dy_re_[v]) * dy_re_[v] + double(dy_im_[v]) * dy_im_[v]);
            inv_denom_[size_t(v) * w + u] = d > 0 ? float(1.0 / (d * double(n) * n)) : 0.0f;
        }
}

FrankotChellappa::~FrankotChellappa() {
    std::lock_guard<std::mutex> lock(fftwf_planner());
    if (forward_p_) fftwf_destroy_plan(forward_p_);
    if (forward_q_) fftwf_destroy_plan(forward_q_);
    if (backward_) fftwf_destroy_plan(backward_);
    fftwf_free(real_);
    fftwf_free(real_q_);
    fftwf_free(heights_);
    fftwf_free(spec_p_);
    fftwf_free(spec_q_);
}

void FrankotChellappa::integrate(const std::vector<float>& p, const std::vector<float>& q,
                                 std::vector<float>& h) {
    const size_t count = size_t(n_) * n_;
    std::memcpy(real_, p.data(), count * sizeof(float));
    std::memcpy(real_q_, q.data(), count * sizeof(float));
    integrate();
    h.assign(heights_, heights_ + count);
}

void FrankotChellappa::integrate() {
    using Clock = std::chrono::steady_clock;
    auto t = Clock::now();
    fftwf_execute(forward_p_);
    fftwf_execute(forward_q_);
    fft_seconds_ += std::chrono::duration<double>(Clock::now() - t).count();
    const int w = n_ / 2 + 1;
    parallel_for(0, n_, [&](int v) {
        const float br = wy_ * dy_re_[v], bi = wy_ * dy_im_[v];
        fftwf_complex* P = spec_p_ + size_t(v) * w;
        const fftwf_complex* Q = spec_q_ + size_t(v) * w;
        const float* k = &inv_denom_[size_t(v) * w];
        for (int u = 0; u < w; ++u) {
            const float ar = wx_ * dx_re_[u], ai = wx_ * dx_im_[u];
            // (wx conj(a) P + wy conj(b) Q) / (wx |a|^2 + wy |b|^2)  [R19 Eq. 21, forward
            // differences; wx = wy = 1 is the plain least squares]
            const float re = ar * P[u][0] + ai * P[u][1] + br * Q[u][0] + bi * Q[u][1];
            const float im = ar * P[u][1] - ai * P[u][0] + br * Q[u][1] - bi * Q[u][0];
            P[u][0] = re * k[u];
            P[u][1] = im * k[u];
        }
    });
    t = Clock::now();
    fftwf_execute(backward_); // spec_p_ -> heights_
    fft_seconds_ += std::chrono::duration<double>(Clock::now() - t).count();
}

void FrankotChellappa::autocorrelation(const std::vector<float>& h, std::vector<float>& out) {
    const size_t count = size_t(n_) * n_;
    double mean = 0;
    for (float v : h) mean += v;
    mean /= double(count);
    for (size_t k = 0; k < count; ++k) real_[k] = float(h[k] - mean);
    fftwf_execute(forward_p_);
    const size_t spec = size_t(n_) * (n_ / 2 + 1);
    for (size_t k = 0; k < spec; ++k) {
        spec_p_[k][0] = spec_p_[k][0] * spec_p_[k][0] + spec_p_[k][1] * spec_p_[k][1];
        spec_p_[k][1] = 0.0f;
    }
    fftwf_execute(backward_);
    const float zero = heights_[0];
    out.resize(count);
    for (size_t k = 0; k < count; ++k) out[k] = zero > 0 ? heights_[k] / zero : 0.0f;
}

} // namespace gonio
