#pragma once
// The shared chi-square test of a direction sampler against its pdf (pbrt-v4 and Mitsuba 3 style):
// bin samples on an equal-area Beckers partition of the hemisphere, integrate the pdf over every
// cell for the expected counts, pool low-count cells, and return Pearson's statistic and p-value.
#include "core/chi_square.h"
#include "core/quadrature.h"
#include "core/random.h"
#include "sensor/beckers_sensor.h"
#include "sensor/cell_integral.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace gonio::test {

struct DirectionChiSquare {
    ChiSquareResult chi;
    double pdf_integral = 0; // integral of the pdf over the hemisphere (should be 1)
};

inline DirectionChiSquare chi_square_directions(const std::function<Vec3(double, double)>& sample,
                                                const std::function<double(const Vec3&)>& pdf,
                                                int samples, int cells, std::uint64_t seed) {
    const BeckersSensor sensor(cells);
    std::vector<double> observed(cells, 0.0), expected(cells, 0.0);
    Rng rng{seed, 0x5a3c};
    for (int k = 0; k < samples; ++k) {
        const double u1 = rng.uniform(), u2 = rng.uniform();
        const Vec3 d = sample(u1, u2);
        if (!(d.z >= 0) || !std::isfinite(d.x + d.y + d.z)) { // invalid samples fail the test
            observed.assign(cells, 0.0);
            DirectionChiSquare bad;
            bad.chi.failure = "sampler returned a direction below the horizon or NaN";
            return bad;
        }
        observed[sensor.lookup(d)] += 1;
    }
    // Expected counts: the pdf integrated over each cell. Cells on the horizon get adaptive
    // integrals on pieces shrinking geometrically towards cos theta = 0, where a visible-normal pdf
    // may grow like 1 / cos theta (distributions with D ~ 1 / cos, cut near the horizon).
    std::vector<double> mass = integrate_over_cells(sensor, pdf);
    for (int c = 0; c < cells; ++c) {
        const SensorCell& cell = sensor.cell(c);
        if (cell.theta_max < 0.5 * kPi - 1e-12) continue;
        auto ring = [&](double z) {
            const double r = std::sqrt(std::max(0.0, 1 - z * z));
            return integrate_adaptive(
                [&](double p) {
                    return pdf({r * std::cos(p), r * std::sin(p), z});
                },
                cell.phi_min, cell.phi_max, 1e-15, 1e-6);
        };
        double sum = 0, hi = std::cos(cell.theta_min);
        for (; hi > 1e-9; hi *= 0.25) // expected counts to ~1e-6: far below their noise
            sum += integrate_adaptive(ring, 0.25 * hi, hi, 1e-15, 1e-6);
        mass[c] = sum;
    }
    double total = 0;
    for (int c = 0; c < cells; ++c) {
        expected[c] = mass[c] * samples;
        total += mass[c];
    }
    return {chi_square_test(observed, expected), total};
}

} // namespace gonio::test
