#include "sensor/cell_integral.h"

#include "core/parallel.h"
#include "core/quadrature.h"

#include <cmath>

namespace gonio {

std::vector<double> integrate_over_cells(const BeckersSensor& sensor,
                                         const std::function<double(const Vec3&)>& density) {
    const GaussLegendre& gl = gauss_legendre(8);
    std::vector<double> out(sensor.cell_count(), 0.0);
    // Cells are independent: each is summed in one order, whatever the threads.
    parallel_for(0, sensor.cell_count(), [&](int c) {
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
                               density({r * std::cos(p), r * std::sin(p), z});
                    }
                }
            }
        out[size_t(c)] = sum;
    });
    return out;
}

} // namespace gonio
