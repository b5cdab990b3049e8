#include "heightfield/surface_metrics.h"

#include "core/random.h"
#include "heightfield/frankot_chellappa.h"
#include "sensor/beckers_sensor.h"
#include "sensor/cell_integral.h"

#include <algorithm>
#include <cmath>

namespace gonio {

namespace {

std::vector<double> measured_cell_mass(const HeightField& s, const BeckersSensor& sensor) {
    std::vector<double> mass(sensor.cell_count(), 0.0);
    const double w = 1.0 / (2.0 * s.n * s.n);
    for (int y = 0; y < s.n; ++y)
        for (int x = 0; x < s.n; ++x)
            for (int t = 0; t < 2; ++t) {
                double sp, sq;
                s.triangle_slopes(x, y, t, sp, sq);
                mass[sensor.lookup(HeightField::normal_of_slopes(sp, sq))] += w;
            }
    return mass;
}

double median_abs(std::vector<float>& v) {
    for (float& x : v) x = std::abs(x);
    auto mid = v.begin() + v.size() / 2;
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

// Lag where a 1-D autocorrelation profile first falls below 1/e (linear interpolation).
double correlation_length(const std::vector<float>& acf, int n, bool along_x) {
    const double e = std::exp(-1.0);
    if (!(acf[0] > 0)) return 0; // a flat map: no correlation to measure
    for (int k = 1; k <= n / 2; ++k) {
        const double a = along_x ? acf[k - 1] : acf[size_t(k - 1) * n];
        const double b = along_x ? acf[k] : acf[size_t(k) * n];
        if (b < e) return (k - 1) + (a - e) / (a - b);
    }
    return n / 2.0;
}

} // namespace

std::vector<double> target_cell_mass(const Ndf& ndf, int bins) {
    return integrate_over_cells(BeckersSensor(bins), [&](const Vec3& m) { return ndf.pdf_m(m); });
}

std::vector<double> facet_cell_mass(const HeightField& surface, int bins) {
    return measured_cell_mass(surface, BeckersSensor(bins));
}

void correlation_lengths(const HeightField& s, double& along_x, double& along_y) {
    FrankotChellappa fft(s.n, 1);
    std::vector<float> acf;
    fft.autocorrelation(s.h, acf);
    along_x = correlation_length(acf, s.n, true) * s.spacing;
    along_y = correlation_length(acf, s.n, false) * s.spacing;
}

double total_variation(const std::vector<double>& a, const std::vector<double>& b) {
    double tv = 0;
    for (size_t c = 0; c < a.size(); ++c) tv += std::abs(a[c] - b[c]);
    return 0.5 * tv;
}

double ndf_distance(const HeightField& surface, const Ndf& ndf, int bins) {
    return total_variation(facet_cell_mass(surface, bins), target_cell_mass(ndf, bins));
}

SurfaceMetrics measure_surface(const HeightField& s, const Ndf& ndf, int bins) {
    SurfaceMetrics r;
    const BeckersSensor sensor(bins);
    r.ndf_bins = bins;
    r.measured_mass = measured_cell_mass(s, sensor);
    r.target_mass = target_cell_mass(ndf, bins);
    for (int c = 0; c < bins; ++c)
        r.ndf_distance += 0.5 * std::abs(r.measured_mass[c] - r.target_mass[c]);

    // Slopes of every triangle.
    const size_t tri = size_t(2) * s.n * s.n;
    std::vector<float> px(tri), py(tri);
    double sum_x2 = 0, sum_y2 = 0;
    size_t k = 0;
    for (int y = 0; y < s.n; ++y)
        for (int x = 0; x < s.n; ++x)
            for (int t = 0; t < 2; ++t, ++k) {
                double sp, sq;
                s.triangle_slopes(x, y, t, sp, sq);
                px[k] = float(sp), py[k] = float(sq);
                sum_x2 += sp * sp, sum_y2 += sq * sq;
            }
    r.alpha_rms_x = std::sqrt(2.0 * sum_x2 / tri);
    r.alpha_rms_y = std::sqrt(2.0 * sum_y2 / tri);
    // Target medians from 2^20 samples of the distribution itself (fixed seed).
    const int m = 1 << 20;
    std::vector<float> tx(m), ty(m);
    Rng rng{0x6d656469616eull /* "median" */};
    for (int i = 0; i < m; ++i) {
        const Vec3 n = ndf.sample_m(rng.uniform(), rng.uniform());
        const double z = std::max(n.z, 1e-6);
        tx[i] = float(-n.x / z), ty[i] = float(-n.y / z);
    }
    const double ratio_x = median_abs(px) / median_abs(tx),
                 ratio_y = median_abs(py) / median_abs(ty);
    double ax = 0, ay = 0;
    if (ndf.slope_stretch(ax, ay)) {
        r.target_alpha_x = ax, r.target_alpha_y = ay;
        r.alpha_eff_x = ax * ratio_x, r.alpha_eff_y = ay * ratio_y;
    } else {
        r.alpha_eff_x = ratio_x, r.alpha_eff_y = ratio_y; // a scale ratio to the target
    }

    // Heights.
    double mean = 0;
    r.height_min = 1e300, r.height_max = -1e300;
    for (float v : s.h)
        mean += v, r.height_min = std::min(r.height_min, double(v)),
                   r.height_max = std::max(r.height_max, double(v));
    mean /= double(s.h.size());
    double var = 0;
    for (float v : s.h) var += (v - mean) * (v - mean);
    r.height_rms = std::sqrt(var / double(s.h.size()));
    r.height_histogram.assign(64, 0.0);
    const double span = std::max(1e-30, r.height_max - r.height_min);
    for (float v : s.h)
        r.height_histogram[std::min(63, int((v - r.height_min) / span * 64))] +=
            1.0 / double(s.h.size());
    correlation_lengths(s, r.correlation_length_x, r.correlation_length_y);
    return r;
}

} // namespace gonio
