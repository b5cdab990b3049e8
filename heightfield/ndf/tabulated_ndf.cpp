#include "heightfield/ndf/tabulated_ndf.h"

#include "core/parallel.h"
#include "core/quadrature.h"
#include "core/random.h"
#include "heightfield/exr_io.h"
#include "heightfield/fftw_planner.h"
#include "heightfield/ndf/ndf_family.h"
#include "heightfield/ndf/piecewise_linear.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <fftw3.h>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {
constexpr int kThetaO = 256; // polar-angle intervals of the projected-area table
constexpr int kNodes = 16;   // Gauss-Legendre nodes per table interval in theta_m

// One complex-to-real or real-to-complex transform of length n, planned once.
struct RealFft {
    int n;
    double* real;
    fftw_complex* spectrum;
    fftw_plan forward, backward;
    explicit RealFft(int size) : n(size) {
        std::lock_guard<std::mutex> lock(fftw_planner());
        real = fftw_alloc_real(size_t(n));
        spectrum = fftw_alloc_complex(size_t(n / 2 + 1));
        forward = fftw_plan_dft_r2c_1d(n, real, spectrum, FFTW_ESTIMATE);
        backward = fftw_plan_dft_c2r_1d(n, spectrum, real, FFTW_ESTIMATE);
    }
    ~RealFft() {
        std::lock_guard<std::mutex> lock(fftw_planner());
        fftw_destroy_plan(forward);
        fftw_destroy_plan(backward);
        fftw_free(real);
        fftw_free(spectrum);
    }
    RealFft(const RealFft&) = delete;
    RealFft& operator=(const RealFft&) = delete;
};

// Fourier coefficients k_n = (1/2pi) int max(0, -(a + b cos psi)) cos(n psi) dpsi, n = 0 .. h,
// for a >= 0, b >= 0: the back-facing part of <o.m>, nonzero only where a < b, for
// |psi| > C = acos(-a/b) [R19 Eq. 14]. (<o.m> = o.m + this, and int (o.m) D dw = o.M.)
void kernel_coefficients(double a, double b, int h, std::vector<double>& k) {
    k.assign(size_t(h) + 1, 0.0);
    if (a >= b) return;
    const double c = std::acos(std::clamp(-a / b, -1.0, 1.0)), inv = 1.0 / kTwoPi;
    const double s1 = std::sin(c), c1 = std::cos(c);
    // The clamped kernel's coefficients minus those of a + b cos psi (a and b / 2), written
    // without cancellation: both vanish as C -> pi.
    k[0] = inv * 2 * (b * s1 - a * (kPi - c));
    if (h >= 1) k[1] = inv * (2 * a * s1 - b * (kPi - c - s1 * c1));
    // sin(n C) by the Chebyshev recurrence sin((n+1)C) = 2 cos C sin(nC) - sin((n-1)C).
    double prev = s1, cur = 2 * c1 * s1; // sin C, sin 2C
    for (int n = 2; n <= h; ++n) {
        const double next = 2 * c1 * cur - prev; // sin((n+1)C)
        k[n] = inv * (2 * a * cur / n + b * (prev / (n - 1) + next / (n + 1)));
        prev = cur, cur = next;
    }
}

// Cubic (Catmull-Rom) through p0..p3 at t in [0, 1] between p1 and p2.
double cubic(double p0, double p1, double p2, double p3, double t) {
    return p1 + 0.5 * t *
                    (p2 - p0 + t * (2 * p0 - 5 * p1 + 4 * p2 - p3 + t * (3 * (p1 - p2) + p3 - p0)));
}
} // namespace

TabulatedNdf::TabulatedNdf(NdfTable table, std::string source, std::string kind)
    : t_(std::move(table)), source_(std::move(source)), kind_(std::move(kind)) {
    const int nt = t_.theta_intervals, np = t_.phi_count;
    if (nt < 2 || np < 1 || t_.values.size() != size_t(nt + 1) * np)
        throw std::invalid_argument(kind_ + ": the table's size does not match its grid");
    dt_ = 0.5 * kPi / nt, dp_ = kTwoPi / np;
    // theta = 0 is one direction: its row holds one value.
    double pole = 0;
    for (int k = 0; k < np; ++k) pole += t_.values[k] / np;
    for (int k = 0; k < np; ++k) t_.values[k] = pole;
    // Exact normalisation: the row means are linear in theta [R19 Eq. 12].
    ControlPoints means;
    for (int j = 0; j <= nt; ++j) {
        double m = 0;
        for (int k = 0; k < np; ++k) m += t_.at(j, k) / np;
        means.theta.push_back(j == nt ? 0.5 * kPi : j * dt_);
        means.value.push_back(m);
    }
    const double c = piecewise_linear_normalisation(means);
    if (!(c > 0) || !std::isfinite(c))
        throw std::invalid_argument(kind_ + " " + source_ + ": the table is zero everywhere");
    for (double& v : t_.values) v /= c;

    // Cell masses of D cos sin and D sin^2 (the phi integral of a bilinear cell is exact).
    const GaussLegendre& g = gauss_legendre(8);
    cdf_cos_.resize(size_t(nt) * np);
    cdf_sin_.resize(size_t(nt) * np);
    double acc_cos = 0, acc_sin = 0;
    for (int j = 0; j < nt; ++j)
        for (int k = 0; k < np; ++k) {
            const int k1 = (k + 1) % np;
            const double a0 = 0.5 * dp_ * (t_.at(j, k) + t_.at(j, k1));
            const double a1 = 0.5 * dp_ * (t_.at(j + 1, k) + t_.at(j + 1, k1));
            double mc = 0, ms = 0;
            for (size_t i = 0; i < g.nodes.size(); ++i) {
                const double s = 0.5 * (1 + g.nodes[i]), th = (j + s) * dt_;
                const double w = 0.5 * dt_ * g.weights[i] * (a0 + s * (a1 - a0));
                mc += w * std::cos(th) * std::sin(th);
                ms += w * std::sin(th) * std::sin(th);
            }
            cdf_cos_[size_t(j) * np + k] = acc_cos += mc;
            cdf_sin_[size_t(j) * np + k] = acc_sin += ms;
        }
    sin_mass_ = acc_sin;

    // Projected area I(theta_o, phi_o) on the Fourier series of the rows (see the header).
    ip_ = std::max(256, 4 * np);
    it_ = kThetaO;
    const int h = ip_ / 2 - 1; // harmonics kept: what the phi_o grid resolves (no Nyquist)
    std::vector<std::complex<double>> rows(size_t(nt + 1) * (h + 1));
    {
        RealFft fft(np);
        for (int j = 0; j <= nt; ++j) {
            std::copy(&t_.values[size_t(j) * np], &t_.values[size_t(j) * np] + np, fft.real);
            fftw_execute(fft.forward);
            for (int n = 0; n <= h; ++n) {
                // Spectrum of the periodic piecewise-linear interpolant: the samples' DFT
                // (periodic in n) times the hat function's sinc^2.
                const int r = n % np, m = r <= np / 2 ? r : np - r;
                std::complex<double> x(fft.spectrum[m][0], fft.spectrum[m][1]);
                if (r != m) x = std::conj(x);
                const double arg = kPi * n / np, sinc = n == 0 ? 1.0 : std::sin(arg) / arg;
                rows[size_t(j) * (h + 1) + n] = x * (sinc * sinc / np);
            }
        }
    }
    // M = int m D dw (0 for a distribution symmetric under phi -> phi + pi): its x and y from
    // the first harmonic, int cos(phi) D dphi = 2 pi Re D_1, int sin(phi) D dphi = -2 pi Im D_1.
    mean_x_ = mean_y_ = 0;
    if (h >= 1)
        for (int j = 0; j < nt; ++j)
            for (size_t q = 0; q < g.nodes.size(); ++q) {
                const double s = 0.5 * (1 + g.nodes[q]), th = (j + s) * dt_;
                const std::complex<double> d1 =
                    (1 - s) * rows[size_t(j) * (h + 1) + 1] + s * rows[size_t(j + 1) * (h + 1) + 1];
                const double w = 0.5 * dt_ * g.weights[q] * std::sin(th) * std::sin(th) * kTwoPi;
                mean_x_ += w * d1.real(), mean_y_ -= w * d1.imag();
            }
    projected_.assign(size_t(it_ + 1) * ip_, 0.0);
    const GaussLegendre& gq = gauss_legendre(kNodes);
    parallel_for(0, it_ + 1, [&](int i) {
        const double to = 0.5 * kPi * i / it_, co = std::cos(to), so = std::sin(to);
        const double kink = 0.5 * kPi - to;
        std::vector<std::complex<double>> spectrum(size_t(h) + 1, 0.0);
        std::vector<double> k;
        auto add = [&](int j, double lo, double hi) {
            for (size_t q = 0; q < gq.nodes.size(); ++q) {
                const double tm = 0.5 * (lo + hi) + 0.5 * (hi - lo) * gq.nodes[q];
                const double w = 0.5 * (hi - lo) * gq.weights[q] * std::sin(tm);
                const double s = std::clamp((tm - j * dt_) / dt_, 0.0, 1.0);
                kernel_coefficients(co * std::cos(tm), so * std::sin(tm), h, k);
                const std::complex<double>* r0 = &rows[size_t(j) * (h + 1)];
                const std::complex<double>* r1 = r0 + (h + 1);
                for (int n = 0; n <= h; ++n)
                    spectrum[n] += (w * k[n]) * ((1 - s) * r0[n] + s * r1[n]);
            }
        };
        for (int j = 0; j < nt; ++j) {
            const double lo = j * dt_, hi = j + 1 == nt ? 0.5 * kPi : (j + 1) * dt_;
            if (kink > lo && kink < hi) {
                add(j, lo, kink);
                add(j, kink, hi);
            } else {
                add(j, lo, hi);
            }
        }
        // I(phi_o) = 2 pi (S_0 + 2 sum_n Re(S_n e^{i n phi_o})), by FFTW's inverse transform.
        RealFft fft(ip_);
        for (int n = 0; n <= ip_ / 2; ++n) {
            const std::complex<double> v = n <= h ? spectrum[n] : 0.0;
            fft.spectrum[n][0] = v.real(), fft.spectrum[n][1] = v.imag();
        }
        fftw_execute(fft.backward); // sum_n c_n e^{i n phi}, both signs of n for real output
        for (int l = 0; l < ip_; ++l) projected_[size_t(i) * ip_ + l] = kTwoPi * fft.real[l];
    });
}

double TabulatedNdf::bilinear(double theta, double phi) const {
    const int nt = t_.theta_intervals, np = t_.phi_count;
    const double ft = std::clamp(theta / dt_, 0.0, double(nt));
    const int j = std::min(int(ft), nt - 1);
    const double a = ft - j;
    double fp = phi / dp_;
    fp -= np * std::floor(fp / np);
    const int k = std::min(int(fp), np - 1), k1 = k + 1 == np ? 0 : k + 1;
    const double b = fp - k;
    return (1 - a) * ((1 - b) * t_.at(j, k) + b * t_.at(j, k1)) +
           a * ((1 - b) * t_.at(j + 1, k) + b * t_.at(j + 1, k1));
}

double TabulatedNdf::D(const Vec3& m) const {
    if (m.z <= 0) return 0.0;
    return bilinear(std::acos(std::min(1.0, m.z)), std::atan2(m.y, m.x));
}

double TabulatedNdf::lambda(const Vec3& v) const {
    if (v.z <= 0) return std::numeric_limits<double>::infinity();
    const double theta = std::acos(std::min(1.0, v.z));
    double phi = std::atan2(v.y, v.x);
    if (phi < 0) phi += kTwoPi;
    // Bicubic: Catmull-Rom along phi (periodic) on four rows, then along theta with the ends'
    // ghost rows extrapolated quadratically.
    const double x = theta / (0.5 * kPi) * it_, y = phi / kTwoPi * ip_;
    const int i = std::min(int(x), it_ - 1), l = int(y) % ip_;
    const double tx = x - i, ty = y - std::floor(y);
    // The four (periodic) columns, wrapped once rather than per row.
    const size_t c0 = size_t((l - 1 + ip_) % ip_), c1 = size_t(l), c2 = size_t((l + 1) % ip_),
                 c3 = size_t((l + 2) % ip_);
    auto row = [&](int r) {
        const double* p = &projected_[size_t(r) * ip_];
        return cubic(p[c0], p[c1], p[c2], p[c3], ty);
    };
    double p[4];
    for (int q = 0; q < 4; ++q) {
        const int r = i - 1 + q;
        if (r >= 0 && r <= it_) p[q] = row(r);
    }
    if (i == 0) p[0] = 3 * p[1] - 3 * p[2] + p[3];
    if (i + 2 > it_) p[3] = 3 * p[2] - 3 * p[1] + p[0];
    const double back = std::max(0.0, cubic(p[0], p[1], p[2], p[3], tx));
    // I = o.M + back and Lambda = I / cos theta_o - 1 [R19 section 3.1], with M_z = 1.
    return std::max(0.0, (v.x * mean_x_ + v.y * mean_y_ + back) / v.z);
}

Vec3 TabulatedNdf::sample_weighted(bool cos_weight, double u1, double u2) const {
    const std::vector<double>& cdf = cos_weight ? cdf_cos_ : cdf_sin_;
    const double total = cdf.back(), target = u1 * total;
    const size_t cell = std::min(
        size_t(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin()), cdf.size() - 1);
    const double before = cell ? cdf[cell - 1] : 0.0;
    double a = std::clamp((target - before) / std::max(cdf[cell] - before, 1e-300), 0.0, 1.0);
    double b = u2;
    const int np = t_.phi_count, j = int(cell / np), k = int(cell % np), k1 = (k + 1) % np;
    const double peak = std::max({t_.at(j, k), t_.at(j, k1), t_.at(j + 1, k), t_.at(j + 1, k1)});
    const double lo = j * dt_, hi = (j + 1) * dt_;
    const double s0 = std::sin(lo), s1 = std::sin(std::min(hi, 0.5 * kPi));
    Rng rng{bits_of(u1), bits_of(u2), 0x7461626c65ull /* "table" */};
    for (bool first = true;; first = false) {
        if (!first) a = rng.uniform(), b = rng.uniform();
        double theta;
        if (cos_weight) { // density cos sin: sin^2 theta uniform
            theta = std::asin(std::sqrt(s0 * s0 + a * (s1 * s1 - s0 * s0)));
        } else { // density sin^2: uniform theta, accepted with sin^2 / its maximum
            theta = lo + a * (hi - lo);
            const double s = std::sin(theta);
            if (rng.uniform() * s1 * s1 >= s * s) continue;
        }
        const double phi = (k + b) * dp_;
        if (rng.uniform() * peak < bilinear(theta, phi)) return spherical_direction(theta, phi);
    }
}

Vec3 TabulatedNdf::sample_m(double u1, double u2) const {
    return sample_weighted(true, u1, u2);
}

Vec3 TabulatedNdf::sample_visible(const Vec3& v, double u1, double u2) const {
    // Envelope (cos t_v cos t_m + sin t_v sin t_m) D >= <v.m> D: D cos with weight cos t_v, D sin
    // with weight sin t_v int D sin dw.
    const double cv = std::max(0.0, v.z), sv = std::sqrt(std::max(0.0, 1 - cv * cv));
    const double wc = cv, ws = sv * sin_mass_, pc = wc / (wc + ws);
    Rng rng{bits_of(u1), bits_of(u2), 0x76697369626c65ull};
    for (bool first = true;; first = false) {
        double a = first ? u1 : rng.uniform(), b = first ? u2 : rng.uniform();
        const bool use_cos = first ? a < pc : rng.uniform() < pc;
        if (first) a = std::min(use_cos ? a / pc : (a - pc) / (1 - pc), std::nextafter(1.0, 0.0));
        const Vec3 m = sample_weighted(use_cos, a, b);
        const double st = std::sqrt(std::max(0.0, 1 - m.z * m.z));
        const double envelope = cv * m.z + sv * st;
        if (rng.uniform() * envelope < std::max(0.0, dot(v, m))) return m;
    }
}

std::string TabulatedNdf::describe() const {
    // The values' FNV-1a hash, so that an edited table never reuses a cached surface.
    std::uint64_t hash = 0xcbf29ce484222325ull;
    for (double v : t_.values) {
        std::uint64_t b = bits_of(v);
        for (int i = 0; i < 8; ++i, b >>= 8) hash = (hash ^ (b & 0xff)) * 0x100000001b3ull;
    }
    std::ostringstream s;
    s << kind_ << "(file=" << source_ << ", theta_intervals=" << t_.theta_intervals
      << ", phi_count=" << t_.phi_count << ", hash=" << std::hex << hash << ")";
    return s.str();
}

double TabulatedNdf::narrowest_feature() const {
    return dt_;
}

double TabulatedNdf::widest_feature() const {
    // RMS polar angle of D cos.
    double sum = 0, prev = 0;
    for (size_t c = 0; c < cdf_cos_.size(); ++c) {
        const double theta = (double(c / size_t(t_.phi_count)) + 0.5) * dt_;
        sum += (cdf_cos_[c] - prev) * theta * theta;
        prev = cdf_cos_[c];
    }
    return std::max(dt_, std::sqrt(sum / cdf_cos_.back()));
}

} // namespace gonio

namespace gonio {
namespace {
const Key kTableFile = Key::path("file", "a D(θ, φ) table: text or `.h5` (docs/configuration.md, after the table)");
const Key kMapFile = Key::path("file", "an EXR height map (or normal map) whose facet NDF is used");
const Key kThetaIntervals =
    Key::integer("theta_intervals", {2, 900}, "height_map: the facet table's θ intervals (2°)")
        .fallback(45.0);
const Key kPhiCount =
    Key::integer("phi_count", {1, 3600}, "height_map: the facet table's φ columns (10°)")
        .fallback(36.0);

// A table or map that does not read is reported at its key, before any work.
template <class F>
auto reading(TableReader& r, const Key& key, F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const std::exception& e) {
        r.fail(key.name, e.what());
    }
}
} // namespace

const NdfFamily& tabulated_family() {
    static const NdfFamily f{"tabulated",
                             "a measured D(θ, φ) table",
                             {kTableFile},
                             [](TableReader& r, int) -> std::unique_ptr<Ndf> {
                                 const std::string file = r.path(kTableFile);
                                 return reading(r, kTableFile, [&] {
                                     return std::make_unique<TabulatedNdf>(read_ndf_table(file),
                                                                           file);
                                 });
                             }};
    return f;
}

const NdfFamily& height_map_family() {
    static const NdfFamily f{
        "height_map",
        "the facet NDF of a height map",
        {kMapFile, kThetaIntervals, kPhiCount},
        [](TableReader& r, int) -> std::unique_ptr<Ndf> {
            const std::string file = r.path(kMapFile);
            const int theta_intervals = int(r.integer(kThetaIntervals));
            const int phi_count = int(r.integer(kPhiCount));
            return reading(r, kMapFile, [&] {
                return std::make_unique<TabulatedNdf>(
                    facet_ndf_table(read_height_exr(file), theta_intervals, phi_count), file,
                    "height_map");
            });
        }};
    return f;
}
} // namespace gonio
