#pragma once
// The shared chi-square test of a direction sampler against its pdf (pbrt-v4 and Mitsuba 3 style):
// bin samples on an equal-area Beckers partition of the hemisphere, integrate the pdf over every
// cell for the expected counts, pool low-count cells, and return Pearson's statistic and p-value.
#include "core/chi_square.h"
#include "core/quadrature.h"
#include "core/random.h"
#include "sensor/beckers_sensor.h"

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
    // Expected counts: 8x8 Gauss-Legendre on each quarter of each cell, in (cos theta, phi).
    const GaussLegendre& gl = gauss_legendre(8);
    double total = 0;
    for (int c = 0; c < cells; ++c) {
        const SensorCell& cell = sensor.cell(c);
        const double z0 = std::cos(cell.theta_max), z1 = std::cos(cell.theta_min);
        double sum = 0;
        for (int qz = 0; qz < 2; ++qz)
            for (int qp = 0; qp < 2; ++qp) {
                const double a = z0 + (z1 - z0) * qz / 2, b = z0 + (z1 - z0) * (qz + 1) / 2;
                const double p0 = cell.phi_min + (cell.phi_max - cell.phi_min) * qp / 2;
                const double p1 = cell.phi_min + (cell.phi_max - cell.phi_min) * (qp + 1) / 2;
                for (int i = 0; i < 8; ++i) {
                    const double z = 0.5 * (a + b) + 0.5 * (b - a) * gl.nodes[i];
                    const double r = std::sqrt(std::max(0.0, 1 - z * z));
                    for (int j = 0; j < 8; ++j) {
                        const double p = 0.5 * (p0 + p1) + 0.5 * (p1 - p0) * gl.nodes[j];
                        sum += gl.weights[i] * gl.weights[j] * 0.25 * (b - a) * (p1 - p0) *
                               pdf({r * std::cos(p), r * std::sin(p), z});
                    }
                }
            }
        expected[c] = sum * samples;
        total += sum;
    }
    return {chi_square_test(observed, expected), total};
}

} // namespace gonio::test
