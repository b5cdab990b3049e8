// Kulla & Conty's and Turquin's energy compensations (gonio/model/energy_compensation.h): white
// furnace, the lobe's own albedo, Turquin's scale, the average Fresnel reflectance.
#include "gonio/model/cell_integrator.h"
#include "gonio/model/energy_compensation.h"
#include "gonio/model/microfacet_model.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"

#include <cmath>
#include <doctest/doctest.h>
#include <memory>

using namespace gonio;

namespace {
double total(const std::vector<double>& v, size_t nc, size_t k) {
    double s = 0;
    for (size_t i = k; i < v.size(); i += nc) s += v[i];
    return s;
}
} // namespace

TEST_CASE("energy compensations: perfect mirrors reflect everything (white furnace)") {
    const BeckersSensor sensor(577);
    const CellQuadrature q;
    for (double alpha : {0.2, 0.8, 1.5}) {
        for (bool ggx : {false, true}) {
            std::shared_ptr<const Ndf> ndf;
            if (ggx)
                ndf = std::make_shared<Ggx>(alpha, alpha);
            else
                ndf = std::make_shared<Beckmann>(alpha, alpha);
            const auto table = std::make_shared<const AlbedoTable>(
                AlbedoTable::smith(*ndf, MaskingForm::height_correlated, q));
            for (Compensation kind : {Compensation::kulla_conty, Compensation::turquin}) {
                const auto model = compensated_model(kind, ndf, FresnelTerm::mirror(),
                                                     MaskingForm::height_correlated, q, table);
                for (double ti : {0.0, 30.0, 60.0, 80.0}) {
                    CAPTURE(alpha);
                    CAPTURE(ggx);
                    CAPTURE(int(kind));
                    CAPTURE(ti);
                    const ModelIncidence m =
                        model->evaluate(spherical_direction(radians(ti), 0.4), sensor, 1, 0);
                    // E interpolated (cubic in theta, nodes a degree apart) and the cells'
                    // quadrature (1e-6) are all that is left.
                    CHECK(total(m.energy, 1, 0) == doctest::Approx(1.0).epsilon(2e-5));
                    CHECK(total(m.l1_energy, 1, 0) < 1.0);
                }
            }
        }
    }
}

TEST_CASE("Kulla-Conty: the lobe's albedo is F_ms (1 - E(mu_i)) [Kulla & Conty 2017]") {
    const BeckersSensor sensor(577);
    const CellQuadrature q;
    const auto ndf = std::make_shared<const Ggx>(0.7, 0.7);
    const auto table = std::make_shared<const AlbedoTable>(
        AlbedoTable::smith(*ndf, MaskingForm::height_correlated, q));
    CHECK(table->average > 0.5);
    CHECK(table->average < 1.0);
    const FresnelTerm gold = FresnelTerm::conductor({{0.18, 3.4}, {1.2, 1.8}});
    const std::vector<double> favg = average_fresnel(gold);
    const auto model = compensated_model(Compensation::kulla_conty, ndf, gold,
                                         MaskingForm::height_correlated, q, table);
    for (double ti : {0.0, 45.0, 75.0}) {
        const Vec3 wi = spherical_direction(radians(ti), 1.0);
        const ModelIncidence m = model->evaluate(wi, sensor, 1, 0);
        for (size_t k = 0; k < 2; ++k) {
            const double fa = favg[k], ea = table->average;
            const double fms = fa * fa * ea / (1 - fa * (1 - ea));
            const double lobe = total(m.energy, 2, k) - total(m.l1_energy, 2, k);
            CHECK(lobe == doctest::Approx(fms * (1 - table->at(wi.z))).epsilon(1e-5));
        }
    }
}

TEST_CASE("average Fresnel reflectance: 1 for a mirror, F0 + (1 - F0) / 21 for Schlick") {
    CHECK(average_fresnel(FresnelTerm::mirror())[0] == doctest::Approx(1.0).epsilon(1e-12));
    const std::vector<double> s = average_fresnel(FresnelTerm::schlick({0.04, 0.9}));
    CHECK(s[0] == doctest::Approx(0.04 + 0.96 / 21).epsilon(1e-10));
    CHECK(s[1] == doctest::Approx(0.9 + 0.1 / 21).epsilon(1e-10));
}

TEST_CASE("Turquin: Model L1 scaled by 1 + F0 (1 - E) / E, per channel") {
    const BeckersSensor sensor(145);
    const CellQuadrature q;
    const auto ndf = std::make_shared<const Beckmann>(0.4, 0.9);
    const auto table = std::make_shared<const AlbedoTable>(
        AlbedoTable::smith(*ndf, MaskingForm::height_correlated, q));
    const FresnelTerm f = FresnelTerm::schlick({0.3, 0.95});
    const auto model =
        compensated_model(Compensation::turquin, ndf, f, MaskingForm::height_correlated, q, table);
    const Vec3 wi = spherical_direction(radians(50.0), 0.3);
    const ModelIncidence m = model->evaluate(wi, sensor, 1, 0);
    const double e = table->at(wi.z);
    for (size_t i = 0; i < m.energy.size(); ++i) {
        const double f0 = i % 2 == 0 ? 0.3 : 0.95;
        CHECK(m.energy[i] ==
              doctest::Approx(m.l1_energy[i] * (1 + f0 * (1 - e) / e)).epsilon(1e-12));
    }
}
