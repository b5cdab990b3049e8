// Ashikhmin, Premoze and Shirley's BRDF generator [A00].
#include "core/hemisphere_integral.h"
#include "gonio/model/ashikhmin_model.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/microfacet_model.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/ndf/mixture_ndf.h"

#include <doctest/doctest.h>
#include <memory>

using namespace gonio;

TEST_CASE(
    "A00 g(k) [Eq. 18] of a height field's D is Smith's projected area (k.n)(1 + Lambda(k))") {
    const Beckmann beckmann(0.3, 0.3), aniso(0.2, 0.5);
    const Ggx ggx(0.5, 0.5);
    for (const Ndf* ndf : std::vector<const Ndf*>{&beckmann, &aniso, &ggx}) {
        CAPTURE(ndf->describe());
        const AshikhminModel model(density_of(*ndf), FresnelTerm::mirror(), {});
        CHECK(model.isotropic() == (ndf != &aniso));
        CHECK(model.mean_cosine() == doctest::Approx(1.0).epsilon(1e-8)); // int D (h.n) = 1
        for (double t : {0.0, 20.0, 55.0, 75.0, 87.0})
            for (double p : {0.0, 37.0, 100.0}) {
                CAPTURE(t);
                CAPTURE(p);
                const Vec3 k = spherical_direction(radians(t), radians(p));
                const double smith = k.z * (1 + ndf->lambda(k));
                CHECK(model.g_exact(k) == doctest::Approx(smith).epsilon(1e-7));
                CHECK(model.g(k) == doctest::Approx(smith).epsilon(2e-3)); // 1-degree table
            }
    }
}

TEST_CASE("A00 Eq. 26 from a height field's D is Model L1 with uncorrelated Smith masking") {
    const Beckmann ndf(0.4, 0.4);
    const FresnelTerm gold = FresnelTerm::conductor({{0.18, 3.4}});
    const AshikhminModel a00(density_of(ndf), gold, {});
    const MicrofacetModel smith(ndf, gold, MaskingForm::uncorrelated);
    for (auto [ti, to, dphi] : {std::tuple{0.0, 30.0, 180.0},
                                {45.0, 45.0, 180.0},
                                {70.0, 80.0, 150.0},
                                {30.0, 60.0, 90.0}}) {
        const Vec3 i = spherical_direction(radians(ti), 0.0);
        const Vec3 o = spherical_direction(radians(to), radians(dphi));
        double a = 0, b = 0;
        a00.eval(i, o, &a);
        smith.eval(i, o, &b);
        CHECK(a == doctest::Approx(b).epsilon(3e-3)); // the g tables' interpolation
    }
}

TEST_CASE("A00: reciprocal, and energy conserving [section 5.3] for several distributions") {
    const Beckmann beckmann(0.3, 0.3);
    const Ggx ggx(0.5, 0.5);
    std::vector<std::unique_ptr<Ndf>> parts;
    parts.push_back(std::make_unique<Beckmann>(0.1, 0.1));
    parts.push_back(std::make_unique<Beckmann>(0.4, 0.4));
    const MixtureNdf mixture(std::move(parts), {0.7, 0.3});
    std::vector<NormalDensity> densities{density_of(beckmann), density_of(ggx), density_of(mixture),
                                         satin_density()};
    AshikhminSettings correlated;
    correlated.correlation_width = radians(15.0);
    correlated.diffuse = AshikhminDiffuse::dielectric;
    correlated.theta_nodes = 31, correlated.phi_nodes = 8; // R(k) is integrated exactly below
    for (const NormalDensity& p : densities) {
        CAPTURE(p.description);
        const AshikhminModel model(p, FresnelTerm::mirror(), correlated);
        for (auto [ti, to, dphi] :
             {std::tuple{10.0, 50.0, 5.0}, {75.0, 40.0, 160.0}, {85.0, 85.0, 0.0}}) {
            const Vec3 i = spherical_direction(radians(ti), radians(20.0));
            const Vec3 o = spherical_direction(radians(to), radians(20.0 + dphi));
            double a = 0, b = 0;
            model.eval(i, o, &a);
            model.eval(o, i, &b);
            CHECK(a == doctest::Approx(b).epsilon(1e-12));
        }
        // A perfect mirror with the correlated term (t = 1 is A00's worst case): R(k) <= 1.
        for (double t : {0.0, 40.0, 70.0, 85.0, 89.0}) {
            CAPTURE(t);
            const double r =
                model.reflectance_exact(spherical_direction(radians(t), radians(30.0)), 0);
            CHECK(r > 0.3);
            CHECK(r <= 1.0 + 1e-6);
        }
    }
}

TEST_CASE("A00 velvet [Eq. 35]: reciprocal, and retroreflective with the correlated term") {
    AshikhminSettings s;
    s.correlation_width = radians(15.0);
    s.theta_nodes = 31;
    const AshikhminModel velvet(velvet_density(0.5), FresnelTerm::schlick({0.05}), s);
    CHECK(velvet.isotropic());
    const Vec3 i = spherical_direction(radians(70.0), 0.0);
    const Vec3 o = spherical_direction(radians(40.0), radians(170.0));
    double a = 0, b = 0;
    velvet.eval(i, o, &a);
    velvet.eval(o, i, &b);
    CHECK(a == doctest::Approx(b).epsilon(1e-12));
    // Fibres lying down reflect grazing light back towards it [A00 section 6.4].
    double back = 0, forward = 0;
    velvet.eval(i, spherical_direction(radians(70.0), 0.0), &back);
    velvet.eval(i, spherical_direction(radians(70.0), kPi), &forward);
    CHECK(back > forward);
}

TEST_CASE("A00 diffuse term [Eq. 28-30]: a white surface returns everything, a metal keeps f0") {
    const Ggx ndf(0.4, 0.4);
    const BeckersSensor sensor(577);
    for (AshikhminDiffuse kind : {AshikhminDiffuse::dielectric, AshikhminDiffuse::metal}) {
        CAPTURE(int(kind));
        AshikhminSettings s;
        s.diffuse = kind;
        const FresnelTerm fresnel = kind == AshikhminDiffuse::metal
                                        ? FresnelTerm::schlick({0.9})
                                        : FresnelTerm::dielectric({1.5});
        const AshikhminModel model(density_of(ndf), fresnel, s);
        AshikhminSettings bare = s;
        bare.diffuse = AshikhminDiffuse::none;
        const AshikhminModel specular(density_of(ndf), fresnel, bare);
        double f0 = 0;
        fresnel.eval(1.0, &f0);
        for (double t : {0.0, 45.0, 80.0}) {
            CAPTURE(t);
            const Vec3 i = spherical_direction(radians(t), 0.0);
            const double total = albedo_from_cells(model_cell_energy(model, i, sensor, {}), 1)[0];
            const double r_cells =
                albedo_from_cells(model_cell_energy(specular, i, sensor, {}), 1)[0];
            const double r = model.reflectance(i, 0);
            // Expected: R + (1 - R) (white), R + f0 (f0 - R) (metal, rho_d = f0); the model uses
            // the tabulated R, the cells integrate rho_s: they differ by the table's error.
            const double expected = kind == AshikhminDiffuse::metal
                                        ? r_cells + f0 * std::max(0.0, f0 - r)
                                        : r_cells + (1 - r);
            CHECK(std::abs(total - expected) <= 1e-5);
            CHECK(std::abs(r - r_cells) <= 2e-3);
            if (kind == AshikhminDiffuse::dielectric)
                CHECK(total == doctest::Approx(1.0).epsilon(2e-3));
        }
    }
}
