#include "core/chi_square.h"
#include "gonio/material/fresnel.h"
#include "gonio/material/interfaced_lambertian.h"
#include "gonio/trace/gonioreflectometer.h"
#include "heightfield/generate.h"
#include "heightfield/ndf/beckmann.h"
#include "sensor/cell_integral.h"

#include <cmath>
#include <doctest/doctest.h>
#include <tbb/global_control.h>

using namespace gonio;

namespace {
HeightField beckmann_surface(double alpha, int n = 256) {
    SurfaceSpec s;
    s.size = n;
    s.iterations = 100;
    return generate_surface(Beckmann(alpha), s, 2);
}
} // namespace

TEST_CASE("flat surface: exactly the Fresnel reflectance into the specular cell") {
    const HeightField flat(32, 1.0);
    const Scene scene(flat);
    const BeckersSensor sensor(3240);
    const std::complex<double> gold{0.21, 3.272};
    const SpecularReflector conductor(FresnelTerm::conductor({gold, {0.43, 2.455}}));
    const SpecularReflector mirror(FresnelTerm::mirror());
    for (double theta : {0.0, 30.0, 60.0, 89.0}) {
        CAPTURE(theta);
        const Vec3 wi = spherical_direction(radians(theta), radians(20.0));
        const int specular = sensor.lookup({-wi.x, -wi.y, wi.z});
        TraceSettings st;
        st.rays = 4096;
        const TraceResult m = trace_incidence(scene, mirror, sensor, wi, st);
        CHECK(m.energy[size_t(specular)] == doctest::Approx(1.0).epsilon(1e-12));
        const TraceResult c = trace_incidence(scene, conductor, sensor, wi, st);
        for (int k = 0; k < 2; ++k) {
            const double F =
                fresnel_conductor(wi.z, k == 0 ? gold : std::complex<double>{0.43, 2.455});
            CHECK(c.energy[size_t(specular) * 2 + k] == doctest::Approx(F).epsilon(1e-12));
            CHECK(c.ledger.absorbed[k] == doctest::Approx(1 - F).epsilon(1e-12));
            CHECK(std::abs(c.ledger.unaccounted[k]) < 1e-12);
        }
    }
}

TEST_CASE("perfect mirror microfacets lose nothing: the ledger closes at every incidence") {
    const BeckersSensor sensor(1000);
    const SpecularReflector mirror(FresnelTerm::mirror());
    for (double alpha : {0.1, 0.5, 1.0}) {
        const Scene scene(beckmann_surface(alpha));
        for (double theta : {0.0, 45.0, 80.0, 89.0}) {
            TraceSettings st;
            st.rays = 1 << 18;
            const TraceResult r = trace_incidence(scene, mirror, sensor,
                                                  spherical_direction(radians(theta), 0.4), st);
            double reflected = 0;
            for (int o = 0; o < r.orders; ++o) reflected += r.ledger.reflected[o];
            CAPTURE(alpha);
            CAPTURE(theta);
            CAPTURE(r.ledger.lost[0]);
            CHECK(reflected >= 1 - 1e-6);
            CHECK(std::abs(r.ledger.unaccounted[0]) <= 1e-6);
            CHECK(r.ledger.lost[0] <= 1e-6);
            CHECK(r.ledger.capped[0] == 0.0);
        }
    }
}

TEST_CASE("tracing gives identical results with 1 and 2 threads") {
    const Scene scene(beckmann_surface(0.5, 64));
    const BeckersSensor sensor(145);
    const SpecularReflector gold(FresnelTerm::conductor({{0.21, 3.272}}));
    const DielectricFacet glass(1.5); // a random choice at every facet
    TraceSettings st;
    st.rays = 50000;
    st.block = 100; // 500 blocks: more than one merge batch
    const Vec3 wi = spherical_direction(radians(50.0), 0.0);
    TraceResult one, glass_one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = trace_incidence(scene, gold, sensor, wi, st);
        glass_one = trace_incidence(scene, glass, sensor, wi, st);
    }
    const TraceResult two = trace_incidence(scene, gold, sensor, wi, st);
    CHECK(one.energy == two.energy);
    CHECK(one.ledger.absorbed == two.ledger.absorbed);
    const TraceResult glass_two = trace_incidence(scene, glass, sensor, wi, st);
    CHECK(glass_one.energy == glass_two.energy);
    CHECK(glass_one.transmitted == glass_two.transmitted);
    CHECK(glass_one.segments == glass_two.segments);
    st.seed = 2;
    CHECK(trace_incidence(scene, gold, sensor, wi, st).energy != two.energy);
}

TEST_CASE("reciprocity: f(i, o) = f(o, i) within the Monte Carlo error") {
    // All orders (L-infinity): reciprocity holds for the whole BRDF. A cell's BRDF is
    // E_c / Omega_c^perp; its Monte Carlo standard error comes from the cell's ray count.
    const Scene scene(beckmann_surface(0.5));
    const BeckersSensor sensor(400);
    const SpecularReflector mirror(FresnelTerm::mirror());
    TraceSettings st;
    st.rays = 1 << 21;
    st.orders = 1; // L1 and one overflow order: their sum is L-infinity
    // Pairs of directions (theta, phi in degrees) with a lobe between them.
    const double pairs[][4] = {{30, 0, 40, 180}, {60, 90, 20, 250}, {70, 10, 50, 200}};
    for (const auto& pair : pairs) {
        const SensorCell& a =
            sensor.cell(sensor.lookup(spherical_direction(radians(pair[0]), radians(pair[1]))));
        const SensorCell& b =
            sensor.cell(sensor.lookup(spherical_direction(radians(pair[2]), radians(pair[3]))));
        auto brdf = [&](const SensorCell& from, const SensorCell& to, double& error) {
            const TraceResult r = trace_incidence(scene, mirror, sensor, from.center, st);
            const int c = sensor.lookup(to.center);
            const double e = r.energy[size_t(c)] + r.energy[size_t(sensor.cell_count() + c)];
            const double rays = e * double(r.rays); // each ray carries 1 / rays (mirror)
            error = std::sqrt(std::max(rays, 1.0)) / double(r.rays) / to.projected_solid_angle;
            return e / to.projected_solid_angle;
        };
        double ea, eb;
        const double fab = brdf(a, b, ea), fba = brdf(b, a, eb);
        CAPTURE(pair[0]);
        CAPTURE(pair[2]);
        CAPTURE(fab);
        CAPTURE(fba);
        CHECK(fab > 0);
        CHECK(std::abs(fab - fba) < 4 * std::sqrt(ea * ea + eb * eb));
    }
}

TEST_CASE("Lambertian facets reflect at most their albedo, and the ledger closes") {
    const Scene scene(beckmann_surface(0.5));
    const BeckersSensor sensor(145);
    const LambertianFacet white({1.0}), grey({0.6, 0.3});
    for (double theta : {0.0, 60.0, 89.0}) {
        const Vec3 wi = spherical_direction(radians(theta), 0.0);
        TraceSettings st;
        st.rays = 1 << 16;
        CAPTURE(theta);
        const TraceResult w = trace_incidence(scene, white, sensor, wi, st);
        double total = 0;
        for (int o = 0; o < w.orders; ++o) total += w.ledger.reflected[o];
        // Albedo 1: nothing is absorbed; all leaves, unless cut by the bounce cap.
        CHECK(total + w.ledger.capped[0] == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(w.ledger.lost[0] == 0.0);
        const TraceResult g = trace_incidence(scene, grey, sensor, wi, st);
        for (int k = 0; k < 2; ++k) {
            double reflected = 0;
            for (int o = 0; o < g.orders; ++o) reflected += g.ledger.reflected[size_t(o) * 2 + k];
            CHECK(reflected <= (k == 0 ? 0.6 : 0.3) + 1e-12);
            CHECK(std::abs(g.ledger.unaccounted[k]) < 1e-12);
            CHECK(g.ledger.lost[k] == 0.0);
        }
        // Single scattering of a Lambertian facet: order 1 carries albedo x (its visible share).
        CHECK(g.ledger.reflected[0] / g.ledger.reflected[1] == doctest::Approx(2.0).epsilon(1e-12));
    }
}

TEST_CASE("interfaced Lambertian facets [M18]: K_d = 1 loses nothing, and n = 1 is Lambertian") {
    const Scene scene(beckmann_surface(0.5));
    const BeckersSensor sensor(145);
    const InterfacedLambertianFacet white({1.5}, {1.0}), plain({1.0}, {0.6}), grey({1.5}, {0.6});
    const LambertianFacet lambert({0.6});
    for (double theta : {0.0, 60.0, 89.0}) {
        const Vec3 wi = spherical_direction(radians(theta), 0.0);
        TraceSettings st;
        st.rays = 1 << 16;
        CAPTURE(theta);
        const TraceResult w = trace_incidence(scene, white, sensor, wi, st);
        double total = 0;
        for (int o = 0; o < w.orders; ++o) total += w.ledger.reflected[o];
        // Interface plus substrate of reflectance 1 conserve energy ray by ray.
        CHECK(total + w.ledger.capped[0] == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(w.ledger.absorbed[0] == doctest::Approx(0.0));
        // n = 1: no interface; the same streams give the Lambertian facet's numbers.
        const TraceResult p = trace_incidence(scene, plain, sensor, wi, st);
        const TraceResult l = trace_incidence(scene, lambert, sensor, wi, st);
        for (int o = 0; o < p.orders; ++o)
            CHECK(p.ledger.reflected[o] == doctest::Approx(l.ledger.reflected[o]).epsilon(1e-12));
        // With n = 1.5 the interface reflects some light specularly and keeps some inside:
        // the ledger still closes.
        const TraceResult g = trace_incidence(scene, grey, sensor, wi, st);
        CHECK(std::abs(g.ledger.unaccounted[0]) < 1e-9);
        CHECK(g.ledger.lost[0] == 0.0);
    }
}

TEST_CASE("a flat interfaced Lambertian surface is M18 Eq. 9: Fresnel spike plus T(i) T(o) body") {
    const HeightField flat(32, 1.0);
    const Scene scene(flat);
    const BeckersSensor sensor(577);
    const InterfacedLambertianFacet il({1.5}, {1.0}); // every ray keeps weight 1: counts
    const double re = il.external_diffuse_reflectance(0);
    for (double theta : {0.0, 50.0, 80.0}) {
        CAPTURE(theta);
        const Vec3 wi = spherical_direction(radians(theta), radians(20.0));
        const int specular = sensor.lookup({-wi.x, -wi.y, wi.z});
        TraceSettings st;
        st.rays = 1 << 18;
        const TraceResult r = trace_incidence(scene, il, sensor, wi, st);
        const double rays = double(st.rays), f = fresnel_dielectric(wi.z, 1.5);
        // Body exits per cell: (1 - F(i)) int T(o) cos / (pi (1 - r_e)) [M18 Eq. 9, normalised].
        const std::vector<double> body = integrate_over_cells(sensor, [&](const Vec3& o) {
            return (1 - fresnel_dielectric(o.z, 1.5)) * o.z / (kPi * (1 - re));
        });
        std::vector<double> observed, expected;
        for (int c = 0; c < sensor.cell_count(); ++c) {
            observed.push_back(r.energy[size_t(c)] * rays); // order 1 only: a flat surface
            expected.push_back(rays * ((1 - f) * body[c] + (c == specular ? f : 0.0)));
        }
        const ChiSquareResult chi = chi_square_test(observed, expected);
        CAPTURE(chi.p_value);
        CHECK(chi.failure.empty());
        CHECK(chi.p_value > 0.01 / 3);
        for (int o = 1; o < r.orders; ++o) CHECK(r.ledger.reflected[o] == 0.0);
    }
}
