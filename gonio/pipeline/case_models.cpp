#include "gonio/pipeline/case_models.h"

#include "core/batch_means.h"
#include "gonio/model/ashikhmin_model.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/interfaced_lambertian_model.h"
#include "gonio/model/microfacet_model.h"
#include "gonio/model/pbrdf_model.h"
#include "gonio/model/vcavity_estimator.h"

#include <chrono>
#include <stdexcept>

namespace gonio {

CaseModels::CaseModels(const CaseConfig& c, const Ndf& ndf, const HeightField* surface)
    : c_(c), ndf_(ndf) {
    for (const ModelChoice& choice : c.model.models) {
        ModelResult r;
        r.name = choice.name;
        r.compared_with = choice.compared_with;
        r.description = choice.description;
        if (choice.needs_surface && !surface)
            throw std::logic_error("model " + choice.name + " is fitted to the case's surface");
        if (choice.build) {
            analytic_.push_back(choice.build(surface));
        } else { // a Monte Carlo estimator: the V-cavity, on the case's (opaque) facets
            analytic_.push_back(nullptr);
            facet_ = std::move(c.material.parts()[0]);
        }
        results_.push_back(std::move(r));
    }
    last_.resize(results_.size());
}

CaseModels::~CaseModels() = default;

std::vector<std::vector<double>> CaseModels::evaluate(const Vec3& wi, const BeckersSensor& sensor,
                                                      std::uint64_t seed, std::uint64_t stream) {
    const size_t nt = c_.theta_i_deg.size(), np = c_.phi_i_deg.size();
    const size_t nc = size_t(c_.channels()), ncell = size_t(sensor.cell_count());
    if (evaluated_ == nt * np) throw std::logic_error("CaseModels: more incidences than the sweep");
    const size_t t = evaluated_ / np, p = evaluated_ % np;
    const bool first_incidence = evaluated_ == 0;
    ++evaluated_;
    // Energy over the cell's projected solid angle, [cell][channel].
    auto brdf_of = [&](std::vector<double> v) {
        for (size_t k = 0; k < v.size(); ++k)
            v[k] /= sensor.cell(static_cast<int>((k / nc) % ncell)).projected_solid_angle;
        return v;
    };
    const std::vector<std::string> cells{"theta_i", "phi_i", "cell", "channel"},
        channels{"theta_i", "phi_i", "channel"};
    std::vector<std::vector<double>> albedos;
    for (size_t k = 0; k < results_.size(); ++k) {
        ModelResult& r = results_[k];
        const bool monte_carlo = !analytic_[k];
        if (first_incidence) {
            r.brdf = Array(cells, {nt, np, ncell, nc}, "1/sr", r.description + ": cell averages");
            r.energy = r.brdf.like("1", r.description + ": fraction of the incident power");
            r.albedo = Array(channels, {nt, np, nc}, "1", r.description + ": directional albedo");
            r.seconds = Array({"theta_i", "phi_i"}, {nt, np}, "s", "wall time of the evaluation");
            if (monte_carlo) {
                r.brdf_stderr = r.brdf.like("1/sr", "standard error of the cell averages (batch "
                                                    "means)");
                r.albedo_stderr = r.albedo.like("1", "standard error of the albedo (batch means)");
                r.l1 = r.brdf.like("1/sr", "single scattering in V-cavities");
                r.l1_albedo = r.albedo.like("1", "single-scattering albedo");
                r.l2_albedo = r.albedo.like("1", "second-order albedo");
                r.l2plus_albedo = r.albedo.like("1", "multiple-scattering albedo");
            }
        }
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<double> energy;
        ModelMap& last = last_[k];
        if (!monte_carlo) {
            energy = model_cell_energy(*analytic_[k], wi, sensor, c_.model.quadrature);
            last.relative_tolerance = c_.model.quadrature.rel_tol;
        } else {
            TraceSettings st;
            st.rays = c_.model.models[k].rays;
            st.orders = 2; // f1, f2, then every higher order together [M18 Fig. 9]
            st.max_bounces = c_.trace.max_bounces;
            st.seed = seed, st.stream = stream;
            const TraceResult v = vcavity_estimate(ndf_, *facet_, sensor, wi, st);
            const int no = v.orders;
            // Sums over orders of the means, [order][n] (one batch), and of the batches.
            auto orders = [&](const std::vector<double>& x, int from, int to) {
                return sum_orders(x, 1, no, from, to);
            };
            energy = orders(v.energy, 0, no);
            r.l1.put({t, p}, brdf_of(orders(v.energy, 0, 1)));
            r.l1_albedo.put({t, p}, orders(v.ledger.reflected, 0, 1));
            r.l2_albedo.put({t, p}, orders(v.ledger.reflected, 1, 2));
            r.l2plus_albedo.put({t, p}, orders(v.ledger.reflected, 1, no));
            last.batches = v.batches;
            last.energy_batches = sum_orders(v.energy_batches, v.batches, no, 0, no);
            r.brdf_stderr.put({t, p}, brdf_of(batch_stderr(last.energy_batches, v.batches)));
            r.albedo_stderr.put(
                {t, p}, batch_stderr(sum_orders(v.ledger_batches.reflected, v.batches, no, 0, no),
                                     v.batches));
        }
        last.energy = energy;
        const std::vector<double> albedo = albedo_from_cells(energy, int(nc));
        r.brdf.put({t, p}, brdf_of(energy));
        r.energy.put({t, p}, energy);
        r.albedo.put({t, p}, albedo);
        r.seconds.at({t, p}) =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        albedos.push_back(albedo);
    }
    return albedos;
}

} // namespace gonio
