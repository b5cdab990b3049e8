#include "gonio/io/model_result.h"

#include "core/batch_means.h"
#include "core/check.h"
#include "gonio/model/cell_integrator.h"

#include <algorithm>

namespace gonio {

void ModelResult::allocate(size_t nt, size_t np, size_t ncell, size_t nc, bool monte_carlo) {
    const std::vector<std::string> cells{"theta_i", "phi_i", "cell", "channel"},
        channels{"theta_i", "phi_i", "channel"};
    brdf = Array(cells, {nt, np, ncell, nc}, "1/sr", description + ": cell averages");
    energy = brdf.like("1", description + ": fraction of the incident power");
    albedo = Array(channels, {nt, np, nc}, "1", description + ": directional albedo");
    seconds = Array({"theta_i", "phi_i"}, {nt, np}, "s", "wall time of the evaluation");
    if (!monte_carlo) return;
    brdf_stderr = brdf.like("1/sr", "standard error of the cell averages (batch means)");
    albedo_stderr = albedo.like("1", "standard error of the albedo (batch means)");
    l1 = brdf.like("1/sr", "single scattering in V-cavities");
    l1_albedo = albedo.like("1", "single-scattering albedo");
    l2_albedo = albedo.like("1", "second-order albedo");
    l2plus_albedo = albedo.like("1", "multiple-scattering albedo");
}

void ModelResult::put(size_t t, size_t p, const ModelIncidence& m,
                      const std::vector<double>& projected_solid_angle) {
    const size_t nc = albedo.extent("channel"), ncell = projected_solid_angle.size();
    GONIO_CHECK(m.energy.size() == ncell * nc);
    GONIO_CHECK(m.monte_carlo() == !l1.empty());
    tolerance_reached = std::max(tolerance_reached, m.relative_tolerance);
    auto brdf_of = [&](std::vector<double> v) {
        return cell_brdf(std::move(v), projected_solid_angle, nc);
    };
    if (m.monte_carlo()) {
        l1.put({t, p}, brdf_of(m.l1_energy));
        l1_albedo.put({t, p}, m.l1_albedo);
        l2_albedo.put({t, p}, m.l2_albedo);
        l2plus_albedo.put({t, p}, m.l2plus_albedo);
        brdf_stderr.put({t, p}, brdf_of(batch_stderr(m.energy_batches, m.batches)));
        albedo_stderr.put({t, p}, m.albedo_stderr);
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
