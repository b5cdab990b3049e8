#include "gonio/io/model_result.h"

#include "core/batch_means.h"
#include "core/check.h"
#include "gonio/model/cell_integrator.h"

#include <algorithm>

namespace gonio {

void ModelResult::allocate(size_t nt, size_t np, size_t ncell, size_t nc,
                           const ModelIncidence& first) {
    const std::vector<std::string> cells{"theta_i", "phi_i", "cell", "channel"},
        channels{"theta_i", "phi_i", "channel"};
    brdf = Array(cells, {nt, np, ncell, nc}, "1/sr", description + ": cell averages");
    energy = brdf.like("1", description + ": fraction of the incident power");
    albedo = Array(channels, {nt, np, nc}, "1", description + ": directional albedo");
    seconds = Array({"theta_i", "phi_i"}, {nt, np}, "s", "wall time of the evaluation");
    if (first.has_orders()) {
        l1 = brdf.like("1/sr", "its single scattering: cell averages");
        l2plus = brdf.like("1/sr", "its orders 2 and up: cell averages");
        l1_albedo = albedo.like("1", "single-scattering albedo");
        l2plus_albedo = albedo.like("1", "multiple-scattering albedo");
    }
    if (!first.monte_carlo()) return;
    if (first.has_orders())
        l2plus_stderr = brdf.like("1/sr", "standard error of the orders 2 and up (batch means)");
    brdf_stderr = brdf.like("1/sr", "standard error of the cell averages (batch means)");
    albedo_stderr = albedo.like("1", "standard error of the albedo (batch means)");
    l2_albedo = albedo.like("1", "second-order albedo");
    const size_t no = ModelIncidence::kOrderBins;
    const std::vector<std::string> per_order{"theta_i", "phi_i", "model_order", "channel"};
    order_albedo = Array(per_order, {nt, np, no, nc}, "1",
                         "reflected albedo of bounce orders 1, 2 and 3 and up");
    order_albedo_stderr = order_albedo.like("1", "standard error of the order albedos");
    if (first.order_transmittance.empty()) return;
    order_transmittance = order_albedo.like("1", "transmitted fraction of orders 1, 2, 3 and up");
    order_transmittance_stderr =
        order_albedo.like("1", "standard error of the transmitted fractions");
}

void ModelResult::put(size_t t, size_t p, const ModelIncidence& m,
                      const std::vector<double>& projected_solid_angle) {
    const size_t nc = albedo.extent("channel"), ncell = projected_solid_angle.size();
    GONIO_CHECK(m.energy.size() == ncell * nc);
    GONIO_CHECK(m.monte_carlo() == !brdf_stderr.empty() && m.has_orders() == !l1.empty());
    GONIO_CHECK(m.order_transmittance.empty() == order_transmittance.empty());
    tolerance_reached = std::max(tolerance_reached, m.relative_tolerance);
    auto brdf_of = [&](std::vector<double> v) {
        return cell_brdf(std::move(v), projected_solid_angle, nc);
    };
    if (m.has_orders()) {
        std::vector<double> rest = m.energy;
        for (size_t i = 0; i < rest.size(); ++i) rest[i] -= m.l1_energy[i];
        l1.put({t, p}, brdf_of(m.l1_energy));
        l2plus.put({t, p}, brdf_of(rest));
        if (m.monte_carlo()) {
            std::vector<double> batches = m.energy_batches;
            for (size_t i = 0; i < batches.size(); ++i) batches[i] -= m.l1_energy_batches[i];
            l2plus_stderr.put({t, p}, brdf_of(batch_stderr(batches, m.batches)));
        }
        // A Monte Carlo model's albedos are its ledger's; an analytic one's its cells' sums.
        l1_albedo.put({t, p},
                      m.monte_carlo() ? m.l1_albedo : albedo_from_cells(m.l1_energy, int(nc)));
        l2plus_albedo.put({t, p},
                          m.monte_carlo() ? m.l2plus_albedo : albedo_from_cells(rest, int(nc)));
    }
    if (m.monte_carlo()) {
        l2_albedo.put({t, p}, m.l2_albedo);
        brdf_stderr.put({t, p}, brdf_of(batch_stderr(m.energy_batches, m.batches)));
        albedo_stderr.put({t, p}, m.albedo_stderr);
        order_albedo.put({t, p}, m.order_albedo);
        order_albedo_stderr.put({t, p}, m.order_albedo_stderr);
        if (!order_transmittance.empty()) {
            order_transmittance.put({t, p}, m.order_transmittance);
            order_transmittance_stderr.put({t, p}, m.order_transmittance_stderr);
        }
    }
    brdf.put({t, p}, brdf_of(m.energy));
    energy.put({t, p}, m.energy);
    albedo.put({t, p}, albedo_from_cells(m.energy, int(nc)));
    seconds.at({t, p}) = m.seconds;
}

double ModelResult::total_seconds() const {
    double s = 0;
    for (double x : seconds.data) s += x;
    return s;
}

} // namespace gonio
