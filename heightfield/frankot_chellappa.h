#pragma once
// Least-squares integration of a periodic gradient field (Frankot & Chellappa 1988; R19 Eq. 20-21)
// with FFTW in single precision. gonio uses the forward-difference form: with a = e^{2 pi i u/n} -
// 1 and b = e^{2 pi i v/n} - 1 the discrete derivatives of h, the minimiser of sum |D_x h - p|^2 +
// |D_y h - q|^2 is H = (conj(a) P + conj(b) Q) / (|a|^2 + |b|^2), H(0,0) = 0. It is exact for the
// forward differences of any periodic surface, and those are the slopes of the triangles rays see
// (heightfield.h); R19 Eq. 21 is its continuous limit, and the central differences of R19 Eq. 22
// would leave a null space at the Nyquist frequency. Plans are made once (FFTW_ESTIMATE, so they do
// not depend on timing) and reused.
#include "heightfield/fftw_planner.h"

#include <fftw3.h>
#include <mutex>
#include <vector>

namespace gonio {

class FrankotChellappa {
  public:
    // n >= 2; threads >= 1 FFTW threads.
    FrankotChellappa(int n, int threads);
    ~FrankotChellappa();
    FrankotChellappa(const FrankotChellappa&) = delete;
    FrankotChellappa& operator=(const FrankotChellappa&) = delete;

    int size() const { return n_; }
    // Weights of the two residuals: minimise wx |D_x h - p|^2 + wy |D_y h - q|^2 (default 1, 1).
    // With wx = 1/ax^2, wy = 1/ay^2 the projection is orthogonal in the stretched slope frame where
    // an anisotropic shape-invariant target is isotropic (the sliced generator's metric).
    void set_metric(double wx, double wy);
    // Heights (zero mean) whose forward differences best match p and q (row-major, n x n, per
    // unit spacing).
    void integrate(const std::vector<float>& p, const std::vector<float>& q, std::vector<float>& h);
    // The same without copies: fill gradient_x() and gradient_y() (n x n each), call integrate();
    // the heights are then in heights().
    float* gradient_x() { return real_; }
    float* gradient_y() { return real_q_; }
    const float* heights() const { return heights_; }
    void integrate();
    // Seconds spent in fftwf_execute alone (the floor of any FFT-based integration).
    double fft_seconds() const { return fft_seconds_; }
    // Circular autocorrelation of h (normalised to 1 at lag 0) into `out`, with the same plans.
    void autocorrelation(const std::vector<float>& h, std::vector<float>& out);

  private:
    int n_;
    float* real_ = nullptr;
    float* real_q_ = nullptr;
    float* heights_ = nullptr;
    double fft_seconds_ = 0;
    fftwf_complex* spec_p_ = nullptr;
    fftwf_complex* spec_q_ = nullptr;
    fftwf_plan forward_p_ = nullptr, forward_q_ = nullptr, backward_ = nullptr;
    std::vector<float> weight_re_, weight_im_; // conj(a)/(|a|^2+|b|^2) per frequency (x part)
    std::vector<float> dx_re_, dx_im_, dy_re_, dy_im_;
    std::vector<float> inv_denom_; // scale / (wx |a|^2 + wy |b|^2) per frequency, 0 at (0, 0)
    float wx_ = 1, wy_ = 1;
};

// Calls fftwf_init_threads once; safe to call repeatedly.
void init_fftw_threads();

} // namespace gonio
