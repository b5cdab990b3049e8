#include "heightfield/heitz_surface.h"

#include "core/check.h"
#include "core/random.h"
#include "heightfield/frankot_chellappa.h"
#include "heightfield/ndf/ndf.h"
#include "heightfield/surface_generator.h"

#include <cmath>
#include <fftw3.h>
#include <mutex>
#include <stdexcept>

namespace gonio {

HeightField heitz_surface(int n, double alpha_x, double alpha_y, double correlation_length,
                          std::uint64_t seed) {
    // surface.size, ndf.alpha and surface.correlation_length, checked where they are read.
    GONIO_CHECK(n >= 2 && correlation_length > 0 && alpha_x > 0 && alpha_y > 0);
    const int w = n / 2 + 1;
    fftwf_complex* spec = fftwf_alloc_complex(size_t(n) * w);
    float* real = fftwf_alloc_real(size_t(n) * n);
    fftwf_plan plan;
    {
        std::lock_guard<std::mutex> lock(fftwf_planner());
        init_fftw_threads();
        fftwf_plan_with_nthreads(1);
        plan = fftwf_plan_dft_c2r_2d(n, n, spec, real, FFTW_ESTIMATE);
    }
    // Gaussian spectrum: amplitude exp(-|k l|^2 / 4) (power exp(-|k l|^2 / 2)), with the
    // correlation length shortened along the rougher axis so the slope ratio follows alpha.
    const double mean_alpha = std::sqrt(alpha_x * alpha_y);
    const double lx = correlation_length * mean_alpha / alpha_x;
    const double ly = correlation_length * mean_alpha / alpha_y;
    for (int v = 0; v < n; ++v) {
        Rng rng{seed, 0x6865697a /* "heiz" */, std::uint64_t(v)};
        const double ky = kTwoPi * (v <= n / 2 ? v : v - n) / n;
        for (int u = 0; u < w; ++u) {
            const double kx = kTwoPi * u / n;
            const double amp = std::exp(-0.25 * (kx * kx * lx * lx + ky * ky * ly * ly));
            // A complex Gaussian coefficient: random phase, Rayleigh modulus (Box-Muller).
            const double r = std::sqrt(-2.0 * std::log1p(-rng.uniform())),
                         phase = kTwoPi * rng.uniform();
            const bool dc = u == 0 && v == 0;
            spec[size_t(v) * w + u][0] = dc ? 0.0f : float(amp * r * std::cos(phase));
            spec[size_t(v) * w + u][1] = dc ? 0.0f : float(amp * r * std::sin(phase));
        }
    }
    fftwf_execute(plan); // c2r keeps the Hermitian part: a real Gaussian field
    HeightField s(n, 1.0);
    s.h.assign(real, real + size_t(n) * n);
    {
        std::lock_guard<std::mutex> lock(fftwf_planner());
        fftwf_destroy_plan(plan);
    }
    fftwf_free(spec);
    fftwf_free(real);
    // Scale so the RMS forward-difference slope along x is alpha_x / sqrt(2) (Beckmann).
    double sum = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) sum += s.p(x, y) * s.p(x, y);
    const double scale = alpha_x / std::sqrt(2.0 * sum / (double(n) * n));
    for (float& v : s.h) v = float(v * scale);
    return s;
}

namespace {
const Key kCorrelation =
    Key::number("correlation_length", {0.5, 1e6}, "heitz: Gaussian correlation length, in samples")
        .fallback(8.0);
const std::vector<Key> kHeitzKeys{kCorrelation};
} // namespace

const SurfaceGenerator& heitz_generator() {
    static const SurfaceGenerator g{
        "heitz",
        "random-phase Gaussian surface (Heitz 2015): Beckmann slopes only",
        &kHeitzKeys,
        [](TableReader& r, const Ndf& ndf, SurfaceSpec& s) {
            double ax, ay;
            if (!ndf.gaussian_slopes(ax, ay))
                r.fail("generator", "\"heitz\" makes Beckmann surfaces only; this case's "
                                    "ndf.type is \"" +
                                        ndf.name() + "\"");
            s.correlation_length = r.number(kCorrelation);
        },
        [](const Ndf& ndf, const SurfaceSpec& s, int, GenerationLog*, const ProgressFn&) {
            double ax, ay;
            const bool gaussian = ndf.gaussian_slopes(ax, ay);
            GONIO_CHECK_MSG(gaussian, "heitz: refused where [surface] is read"); // Beckmann only
            return heitz_surface(s.size, ax, ay, s.correlation_length, s.seed);
        },
        [](const SurfaceSpec& s, std::ostream& o) {
            o << "|correlation_length=" << s.correlation_length;
        },
        [](const SurfaceSpec&) { return true; }};
    return g;
}

} // namespace gonio
