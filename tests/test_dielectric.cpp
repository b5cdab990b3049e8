// Dielectric facets in the tracer: exact Fresnel split on a flat interface, index ratio 1, the
// closed ledger of a rough interface (rays under the surface, total internal reflection), and the
// per-channel tracing of a dispersive index.
#include "gonio/material/fresnel.h"
#include "gonio/trace/gonioreflectometer.h"
#include "heightfield/generate.h"
#include "heightfield/ndf/beckmann.h"

#include <cmath>
#include <doctest/doctest.h>

using namespace gonio;

namespace {
HeightField rough_surface(double alpha) {
    SurfaceSpec s;
    s.size = 128;
    s.iterations = 50;
    return generate_surface(Beckmann(alpha), s, 2);
}
double sum_orders(const std::vector<double>& per_order, int channels = 1, int channel = 0) {
    double total = 0;
    for (size_t o = 0; o * channels < per_order.size(); ++o)
        total += per_order[o * channels + channel];
    return total;
}
} // namespace

TEST_CASE("flat dielectric: Fresnel reflectance into the specular cell, the rest refracted") {
    const Scene scene(HeightField(32, 1.0));
    const BeckersSensor sensor(3240);
    for (double eta : {1.5, 1.0 / 1.33}) {
        const DielectricFacet glass(eta);
        for (double theta : {0.0, 30.0, 60.0, 89.0}) {
            CAPTURE(eta);
            CAPTURE(theta);
            const Vec3 wi = spherical_direction(radians(theta), radians(20.0));
            TraceSettings st;
            st.rays = 1 << 18;
            const TraceResult r = trace_incidence(scene, glass, sensor, wi, st);
            const double F = fresnel_dielectric(wi.z, eta), n = double(r.rays);
            const int specular = sensor.lookup({-wi.x, -wi.y, wi.z});
            const double R = r.energy[size_t(specular)];
            Vec3 wt;
            if (!refract(wi, {0, 0, 1}, eta, wt)) { // beyond the critical angle (eta < 1)
                CHECK(F == 1.0);
                CHECK(R == doctest::Approx(1.0).epsilon(1e-12));
                CHECK(r.ledger.transmitted[0] == 0.0);
                continue;
            }
            const double T = r.transmitted[size_t(sensor.lookup_lower(wt))];
            // Every ray is either reflected or refracted, once: R + T = 1 exactly.
            CHECK(R + T == doctest::Approx(1.0).epsilon(1e-12));
            CHECK(r.ledger.reflected[0] == doctest::Approx(R).epsilon(1e-12));
            CHECK(r.ledger.transmitted[0] == doctest::Approx(T).epsilon(1e-12));
            CHECK(r.ledger.lost[0] == 0.0);
            CHECK(std::abs(r.ledger.unaccounted[0]) < 1e-12);
            // The split is a Bernoulli draw per ray with probability F: R is binomial.
            const double sigma = std::sqrt(F * (1 - F) / n);
            CAPTURE(F);
            CHECK(std::abs(R - F) <= 4 * sigma + 1e-12);
        }
    }
}

TEST_CASE("index ratio 1: a rough interface lets every ray straight through") {
    const Scene scene(rough_surface(0.5));
    const BeckersSensor sensor(1000);
    const DielectricFacet nothing(1.0);
    for (double theta : {0.0, 60.0, 89.0}) {
        const Vec3 wi = spherical_direction(radians(theta), 0.3);
        TraceSettings st;
        st.rays = 1 << 16;
        const TraceResult r = trace_incidence(scene, nothing, sensor, wi, st);
        CAPTURE(theta);
        CHECK(sum_orders(r.ledger.reflected) == 0.0);
        // One crossing (order 1) and out along -wi, possibly after crossing the surface again
        // (a straight ray of a steep incidence re-enters the air through a neighbouring facet).
        CHECK(sum_orders(r.ledger.transmitted) == doctest::Approx(1.0).epsilon(1e-12));
        const int straight = sensor.lookup_lower(-wi);
        double in_cell = 0;
        for (int o = 0; o < r.orders; ++o) in_cell += r.transmitted[size_t(o) * r.cells + straight];
        CHECK(in_cell == doctest::Approx(1.0).epsilon(1e-12));
    }
}

TEST_CASE("rough dielectric: rays under the surface, total internal reflection, ledger closed") {
    const Scene scene(rough_surface(0.5));
    const BeckersSensor sensor(1000);
    const DielectricFacet glass(1.5);
    for (double theta : {0.0, 60.0, 89.0}) {
        const Vec3 wi = spherical_direction(radians(theta), 0.3);
        TraceSettings st;
        st.rays = 1 << 18;
        const TraceResult r = trace_incidence(scene, glass, sensor, wi, st);
        CAPTURE(theta);
        const double R = sum_orders(r.ledger.reflected), T = sum_orders(r.ledger.transmitted);
        CHECK(R + T + r.ledger.capped[0] == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(r.ledger.lost[0] <= 1e-6);
        CHECK(std::abs(r.ledger.unaccounted[0]) < 1e-12);
        CHECK(r.ledger.absorbed[0] == 0.0);
        // Transmission after more than one event (reflection or total internal reflection
        // under the surface) exists on a rough interface, and the reflectance is above the flat
        // surface's only at grazing incidence when the facets turn towards the light.
        CHECK(T > 0.5);
        CHECK(r.ledger.transmitted[1] > 0);
    }
}

TEST_CASE("dispersive dielectric: each channel is traced alone, in order, with its own streams") {
    const Scene scene(rough_surface(0.3));
    const BeckersSensor sensor(145);
    const DielectricFacet blue(1.52), red(1.48);
    const Vec3 wi = spherical_direction(radians(45.0), 0.0);
    TraceSettings st;
    st.rays = 1 << 14;
    st.stream = 7;
    const TraceResult both = trace_incidence(scene, {&blue, &red}, sensor, wi, st);
    REQUIRE(both.channels == 2);
    for (int k = 0; k < 2; ++k) {
        TraceSettings part = st;
        part.stream ^= std::uint64_t(k + 1) << 56;
        const TraceResult one = trace_incidence(scene, k == 0 ? blue : red, sensor, wi, part);
        for (size_t i = 0; i < one.energy.size(); ++i)
            CHECK(both.energy[2 * i + k] == one.energy[i]);
        for (size_t i = 0; i < one.transmitted.size(); ++i)
            CHECK(both.transmitted[2 * i + k] == one.transmitted[i]);
        CHECK(both.ledger.unaccounted[k] == one.ledger.unaccounted[0]);
    }
    // A higher index reflects more.
    CHECK(sum_orders(both.ledger.reflected, 2, 0) > sum_orders(both.ledger.reflected, 2, 1));
}

TEST_CASE("opaque materials have no lower sensor and no transmitted orders") {
    const Scene scene(HeightField(16, 1.0));
    const SpecularReflector mirror(FresnelTerm::mirror());
    TraceSettings st;
    st.rays = 256;
    const TraceResult r = trace_incidence(scene, mirror, BeckersSensor(145), {0, 0, 1}, st);
    CHECK(r.transmitted.empty());
    CHECK(r.ledger.transmitted.empty());
}
