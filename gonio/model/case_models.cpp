#include "gonio/model/case_models.h"

#include "core/batch_means.h"
#include "gonio/material/facet_materials.h"
#include "gonio/model/ashikhmin_model.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/interfaced_lambertian_model.h"
#include "gonio/model/microfacet_model.h"
#include "gonio/model/pbrdf_model.h"
#include "gonio/model/vcavity_estimator.h"

#include <chrono>
#include <stdexcept>

namespace gonio {

namespace {
std::vector<double> interface_eta(const CaseConfig& c) {
    return c.material_type == "lambertian" ? std::vector<double>{1.0} : c.interface_eta;
}
} // namespace

CaseModels::CaseModels(const CaseConfig& c, const Ndf& ndf, const HeightField* surface)
    : c_(c), ndf_(ndf) {
    for (const std::string& name : c.models) {
        ModelResult r;
        r.name = name;
        r.compared_with = "l1";
        if (name == "l1") {
            analytic_.push_back(std::make_unique<MicrofacetModel>(ndf, c.fresnel, c.masking));
            r.description = "Model L1: the specular microfacet BRDF [R19 Eq. 2], masking " +
                            std::string(masking_name(c.masking));
        } else if (name == "il") {
            analytic_.push_back(std::make_unique<InterfacedLambertianModel>(
                ndf, interface_eta(c), c.albedo, c.masking, c.body_points));
            r.description = "interfaced Lambertian microfacets, single scattering f_s + f_b "
                            "[M18 Eq. 12-13], masking " +
                            std::string(masking_name(c.masking));
        } else if (name == "ashikhmin") {
            NormalDensity p = c.ashikhmin_distribution == "satin" ? satin_density()
                              : c.ashikhmin_distribution == "velvet"
                                  ? velvet_density(c.ashikhmin_sigma)
                                  : density_of(ndf);
            r.description = "Ashikhmin-Premoze-Shirley generated BRDF [A00 Eq. 11, 14, 25-30] of " +
                            p.description;
            analytic_.push_back(
                std::make_unique<AshikhminModel>(std::move(p), c.fresnel, c.ashikhmin));
            if (c.ashikhmin.diffuse != "none") r.compared_with = "linf";
        } else if (name == "pbrdf") {
            if (!surface) throw std::logic_error("the P-BRDF is fitted to the case's surface");
            analytic_.push_back(std::make_unique<PBrdfModel>(
                fit_slope_lobes(*surface, c.pbrdf_sigma_eps), c.fresnel));
            r.description = "Chermain et al.'s P-BRDF [C19 Eq. 7, 9, 13-17]: one non-centred "
                            "Beckmann lobe per texel of the surface, the whole patch as footprint";
        } else { // vcavity
            analytic_.push_back(nullptr);
            facet_ = std::move(facet_materials(c)[0]); // opaque: one part
            r.compared_with = "linf";
            r.description = "V-cavity multiple scattering, every order [M18 section 3.3]";
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
            energy = model_cell_energy(*analytic_[k], wi, sensor, c_.quadrature);
            last.relative_tolerance = c_.quadrature.rel_tol;
        } else {
            TraceSettings st;
            st.rays = c_.vcavity_rays;
            st.orders = 2; // f1, f2, then every higher order together [M18 Fig. 9]
            st.max_bounces = c_.max_bounces;
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
