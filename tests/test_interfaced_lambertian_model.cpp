// The analytic interfaced Lambertian model [M18 Eq. 12-13] and its limits.
#include "core/hemisphere_integral.h"
#include "gonio/config/config.h"
#include "gonio/material/fresnel.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/interfaced_lambertian_model.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/gaussian_angles.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/ndf/mixture_ndf.h"
#include "heightfield/ndf/ndf_table.h"
#include "heightfield/ndf/tabulated_ndf.h"

#include <doctest/doctest.h>
#include <memory>

using namespace gonio;

namespace {
double body(const InterfacedLambertianModel& model, const Vec3& i, const Vec3& o) {
    double f = 0;
    model.body_cosine(i, o, &f);
    return f / o.z;
}
} // namespace

TEST_CASE("IL model at n = 1 is the Lambertian-microfacet BRDF: K_d / pi int D G |i.m||o.m| / (i.n "
          "o.n)") {
    const Beckmann ndf(0.5, 0.5);
    const double kd = 0.7;
    for (MaskingForm form : {MaskingForm::height_correlated, MaskingForm::v_cavity}) {
        const InterfacedLambertianModel model(ndf, {1.0}, {kd}, form, 48);
        for (auto [ti, to, dphi] : {std::tuple{0.0, 30.0, 0.0},
                                    {40.0, 60.0, 180.0},
                                    {70.0, 20.0, 90.0},
                                    {60.0, 60.0, 0.0}}) {
            CAPTURE(ti);
            CAPTURE(to);
            CAPTURE(dphi);
            const Vec3 i = spherical_direction(radians(ti), 0.0);
            const Vec3 o = spherical_direction(radians(to), radians(dphi));
            // Brute force in (theta_m, phi_m), independent of the model's sampler-space rule.
            const double reference =
                kd / kPi *
                hemisphere_integral(
                    [&](const Vec3& m) {
                        const double im = dot(i, m), om = dot(o, m);
                        if (im <= 0 || om <= 0) return 0.0;
                        return ndf.D(m) * ndf.G2(i, o, m, form) * im * om / (i.z * o.z);
                    },
                    0.5, &i, 1e-9);
            CHECK(body(model, i, o) == doctest::Approx(reference).epsilon(2e-4));
            double spec = 1;
            model.specular_cosine(i, o, &spec);
            CHECK(spec == 0.0); // no interface: no specular reflection
        }
    }
}

TEST_CASE(
    "IL model as the roughness vanishes: the flat interfaced Lambertian surface [M18 Eq. 9]") {
    const Beckmann ndf(1e-3, 1e-3);
    const InterfacedLambertianModel model(ndf, {1.5}, {0.6}, MaskingForm::height_correlated);
    const Vec3 n{0, 0, 1};
    for (auto [ti, to] : {std::pair{0.0, 30.0}, {45.0, 70.0}, {80.0, 10.0}}) {
        CAPTURE(ti);
        CAPTURE(to);
        const Vec3 i = spherical_direction(radians(ti), 0.0);
        const Vec3 o = spherical_direction(radians(to), radians(130.0));
        CHECK(body(model, i, o) ==
              doctest::Approx(model.facet().body_brdf(i, o, n, 0)).epsilon(1e-4));
    }
    // And on the cells: Fresnel spike + body, albedo F(i) + T(i) K_d (1 - r_i) / (1 - K_d r_i).
    const Beckmann smooth(0.01, 0.01);
    const InterfacedLambertianModel flat(smooth, {1.5}, {0.6}, MaskingForm::height_correlated);
    const BeckersSensor sensor(577);
    for (double ti : {0.0, 60.0}) {
        CAPTURE(ti);
        const Vec3 i = spherical_direction(radians(ti), 0.0);
        const double albedo = albedo_from_cells(model_cell_energy(flat, i, sensor, {}), 1)[0];
        CHECK(albedo == doctest::Approx(flat.facet().albedo(i, n, 0)).epsilon(2e-3));
    }
}

TEST_CASE("IL model: reciprocal, and single scattering never creates energy (M18 Table 2 pairs)") {
    const GaussianAngles gauss(0.5);
    const Beckmann beckmann(0.5, 0.5), rough(1.0, 1.0);
    const Ggx ggx(0.3, 0.3);
    const std::vector<std::pair<const Ndf*, MaskingForm>> cases{
        {&gauss, MaskingForm::v_cavity},
        {&beckmann, MaskingForm::v_cavity},
        {&beckmann, MaskingForm::height_correlated},
        {&rough, MaskingForm::height_correlated},
        {&ggx, MaskingForm::height_correlated},
        {&ggx, MaskingForm::uncorrelated}};
    const BeckersSensor sensor(577);
    for (const auto& [ndf, form] : cases) {
        CAPTURE(ndf->describe());
        CAPTURE(name_of(form));
        const InterfacedLambertianModel model(*ndf, {1.5}, {1.0}, form);
        for (auto [ti, to, dphi] :
             {std::tuple{10.0, 50.0, 30.0}, {75.0, 40.0, 160.0}, {85.0, 85.0, 0.0}}) {
            const Vec3 i = spherical_direction(radians(ti), 0.0);
            const Vec3 o = spherical_direction(radians(to), radians(dphi));
            double a[1], b[1];
            model.eval(i, o, a);
            model.eval(o, i, b);
            CHECK(a[0] == doctest::Approx(b[0]).epsilon(1e-12));
        }
        for (double ti : {0.0, 85.0}) {
            CAPTURE(ti);
            const Vec3 i = spherical_direction(radians(ti), 0.0);
            const double albedo = albedo_from_cells(model_cell_energy(model, i, sensor, {}), 1)[0];
            CHECK(albedo > 0.3);
            CHECK(albedo <= 1.0 + 1e-6);
        }
    }
}

TEST_CASE(
    "IL model body integral for NDFs whose sampler is not a continuous map (table, mixture)") {
    const Beckmann beckmann(0.5, 0.5);
    const TabulatedNdf table(sample_ndf_table(beckmann, 90, 72), "beckmann table");
    std::vector<std::unique_ptr<Ndf>> parts;
    parts.push_back(std::make_unique<Beckmann>(0.1, 0.1));
    parts.push_back(std::make_unique<Ggx>(0.6, 0.6));
    const MixtureNdf mixture(std::move(parts), {0.7, 0.3});
    const InterfacedLambertianFacet facet({1.5}, {0.6});
    for (const Ndf* ndf : std::vector<const Ndf*>{&table, &mixture}) {
        CAPTURE(ndf->describe());
        CHECK(!ndf->continuous_sampler());
        const InterfacedLambertianModel model(*ndf, {1.5}, {0.6}, MaskingForm::height_correlated);
        const Vec3 i = spherical_direction(radians(60.0), 0.0);
        const Vec3 o = spherical_direction(radians(30.0), radians(150.0));
        const double reference = hemisphere_integral(
            [&](const Vec3& m) {
                const double im = dot(i, m), om = dot(o, m);
                if (im <= 0 || om <= 0) return 0.0;
                return ndf->D(m) * ndf->G2(i, o, m, MaskingForm::height_correlated) * im * om /
                       (i.z * o.z) * facet.body_brdf(i, o, m, 0);
            },
            0.1, &i, 1e-9);
        CHECK(body(model, i, o) == doctest::Approx(reference).epsilon(2e-4));
    }
}
