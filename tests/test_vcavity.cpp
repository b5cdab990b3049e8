// The V-cavity multiple-scattering estimator [M18 section 3.3].
#include "core/chi_square.h"
#include "gonio/material/interfaced_lambertian.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/interfaced_lambertian_model.h"
#include "gonio/model/vcavity_estimator.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"

#include <doctest/doctest.h>
#include <tbb/global_control.h>

using namespace gonio;

TEST_CASE("a perfect-mirror V-cavity loses nothing, at every incidence") {
    const SpecularReflector mirror(FresnelTerm::mirror());
    const BeckersSensor sensor(577);
    for (double alpha : {0.3, 1.0, 3.0}) {
        const Beckmann ndf(alpha, alpha);
        for (double ti : {0.0, 60.0, 89.0}) {
            CAPTURE(alpha);
            CAPTURE(ti);
            TraceSettings st;
            st.rays = 1 << 16;
            const TraceResult r =
                vcavity_estimate(ndf, mirror, sensor, spherical_direction(radians(ti), 0.3), st);
            double total = 0;
            for (double e : r.ledger.reflected) total += e;
            CHECK(total == doctest::Approx(1.0).epsilon(1e-12));
            CHECK(r.ledger.lost[0] == 0.0);
            CHECK(r.ledger.capped[0] == 0.0);
            CHECK(r.ledger.absorbed[0] == 0.0);
        }
    }
}

TEST_CASE("V-cavity f1 is the microfacet BRDF with Torrance-Sparrow's G [M18 Eq. 15]: chi-square") {
    const BeckersSensor sensor(577);
    const Beckmann beckmann(0.5, 0.5), rough(1.0, 1.0);
    const Ggx ggx(0.3, 0.3);
    const SpecularReflector mirror(FresnelTerm::mirror());
    const InterfacedLambertianFacet white({1.5}, {1.0}); // every path keeps weight 1: counts
    const std::vector<double> thetas{0.0, 60.0, 80.0};
    int tests = 0;
    for (const Ndf* ndf : std::vector<const Ndf*>{&beckmann, &rough, &ggx})
        for (const Material* material : std::vector<const Material*>{&mirror, &white})
            for (double ti : thetas) {
                CAPTURE(ndf->describe());
                CAPTURE(ti);
                CAPTURE(material == &white);
                const Vec3 wi = spherical_direction(radians(ti), radians(40.0));
                TraceSettings st;
                st.rays = 1 << 18;
                st.seed = 7;
                const TraceResult r = vcavity_estimate(*ndf, *material, sensor, wi, st);
                std::vector<double> expected;
                if (material == &mirror) {
                    const MicrofacetModel model(*ndf, FresnelTerm::mirror(), MaskingForm::v_cavity);
                    expected = model_cell_energy(model, wi, sensor, {});
                } else {
                    const InterfacedLambertianModel model(*ndf, {1.5}, {1.0},
                                                          MaskingForm::v_cavity);
                    expected = model_cell_energy(model, wi, sensor, {});
                }
                std::vector<double> observed(size_t(sensor.cell_count()));
                for (int c = 0; c < sensor.cell_count(); ++c) {
                    observed[size_t(c)] = r.energy[size_t(c)] * double(st.rays); // order 1
                    expected[size_t(c)] *= double(st.rays);
                }
                const ChiSquareResult chi = chi_square_test(observed, expected);
                CAPTURE(chi.statistic);
                CAPTURE(chi.dof);
                CAPTURE(chi.p_value);
                CHECK(chi.failure.empty());
                CHECK(chi.p_value > sidak_level(0.01, 18));
                ++tests;
            }
    CHECK(tests == 18);
}

TEST_CASE("V-cavity: interfaced Lambertian facets with K_d = 1 close the ledger, whatever the "
          "thread count") {
    const BeckersSensor sensor(145);
    const Beckmann ndf(1.0, 1.0);
    const InterfacedLambertianFacet white({1.5}, {1.0});
    const InterfacedLambertianFacet grey({1.5, 1.3}, {0.6, 0.2});
    TraceSettings st;
    st.rays = 100000;
    st.max_bounces = 100000;
    const Vec3 wi = spherical_direction(radians(60.0), 0.0);
    const TraceResult r = vcavity_estimate(ndf, white, sensor, wi, st);
    double total = 0;
    for (double e : r.ledger.reflected) total += e;
    CHECK(total + r.ledger.capped[0] == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(r.ledger.absorbed[0] == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(r.ledger.reflected[1] > 0.02); // rough white facets scatter between each other
    TraceResult one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = vcavity_estimate(ndf, grey, sensor, wi, st);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = vcavity_estimate(ndf, grey, sensor, wi, st);
    }
    CHECK(one.energy == two.energy);
    for (int k = 0; k < 2; ++k) CHECK(std::abs(one.ledger.unaccounted[k]) < 1e-12);
}
