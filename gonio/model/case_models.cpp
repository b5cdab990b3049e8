#include "gonio/model/case_models.h"

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
    std::vector<std::vector<double>> albedos;
    const int nc = c_.channels();
    auto append = [](std::vector<double>& to, const std::vector<double>& v) {
        to.insert(to.end(), v.begin(), v.end());
    };
    for (size_t k = 0; k < results_.size(); ++k) {
        ModelResult& r = results_[k];
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<double> energy;
        ModelMap& last = last_[k];
        if (analytic_[k]) {
            energy = model_cell_energy(*analytic_[k], wi, sensor, c_.model.quadrature);
            last.relative_tolerance = c_.model.quadrature.rel_tol;
        } else {
            TraceSettings st;
            st.rays = c_.model.models[k].rays;
            st.orders = 2; // f1, f2, then every higher order together [M18 Fig. 9]
            st.max_bounces = c_.trace.max_bounces;
            st.seed = seed, st.stream = stream;
            const TraceResult v = vcavity_estimate(ndf_, *facet_, sensor, wi, st);
            const size_t per_order = size_t(sensor.cell_count()) * nc;
            energy.assign(per_order, 0.0);
            for (size_t e = 0; e < v.energy.size(); ++e) energy[e % per_order] += v.energy[e];
            append(r.first_energy, {v.energy.begin(), v.energy.begin() + long(per_order)});
            append(r.l1_albedo, {v.ledger.reflected.begin(), v.ledger.reflected.begin() + nc});
            append(r.l2_albedo,
                   {v.ledger.reflected.begin() + nc, v.ledger.reflected.begin() + 2 * nc});
            std::vector<double> higher(size_t(nc), 0.0);
            for (size_t e = size_t(nc); e < v.ledger.reflected.size(); ++e)
                higher[e % size_t(nc)] += v.ledger.reflected[e];
            append(r.l2plus_albedo, higher);
            last.batches = v.batches;
            last.energy_batches = sum_orders(v.energy_batches, v.batches, v.orders, 0, v.orders);
            append(r.energy_stderr, batch_stderr(last.energy_batches, v.batches));
            append(r.albedo_stderr, batch_stderr(sum_orders(v.ledger_batches.reflected, v.batches,
                                                            v.orders, 0, v.orders),
                                                 v.batches));
        }
        last.energy = energy;
        const std::vector<double> albedo = albedo_from_cells(energy, nc);
        append(r.energy, energy);
        append(r.albedo, albedo);
        r.seconds.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        albedos.push_back(albedo);
    }
    return albedos;
}

} // namespace gonio
