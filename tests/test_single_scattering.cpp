// Simulated single scattering (L1) against what is known exactly and against Smith's model:
// - V-grooves, where the single-bounce escape fraction is exact geometry (Torrance-Sparrow's
//   V-cavity masking is exact for a real V-groove seen across its grooves);
// - a generated Beckmann surface against Model L1 [R19 Eq. 2] with the height-correlated G2
//   [R19 Eq. 9]: the tolerance is the Monte Carlo error plus the model's change over the
//   uncertainty of the surface's effective roughness; beyond it lies Smith's own error.
#include "gonio/model/cell_integrator.h"
#include "gonio/model/microfacet_model.h"
#include "gonio/trace/gonioreflectometer.h"
#include "heightfield/generate.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/surface_metrics.h"

#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>

using namespace gonio;

namespace {
// Grooves along y with facets tilted by +-beta, `period` samples wide; vertices at the kinks, so
// the triangulated surface is exactly the V-groove.
HeightField v_grooves(double beta, int n, int period) {
    HeightField s(n, 1.0);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            s.h[size_t(y) * n + x] = float(std::tan(beta) * std::abs(x % period - period / 2));
    return s;
}

// Single-bounce albedo of symmetric V-grooves (facets tilted by +-beta across the grooves) for
// light in the plane across them: on each facet the lit part and the part whose reflection
// clears the opposite rim are both cut from the bottom by the same wall, so the escaping fraction
// is min(G1(i), G1(o)) with the V-cavity G1 = 2 (n.m)(n.v)/(v.m) [M18 Eq. 15], which is exact for
// a real groove; each facet receives (i.m) A_m / (i.n A) of the beam, A_m / A = 1 / (2 cos beta).
double v_groove_l1(double beta, const Vec3& wi) {
    double total = 0;
    for (double s : {1.0, -1.0}) {
        const Vec3 m{s * std::sin(beta), 0, std::cos(beta)};
        const Vec3 o = reflect(wi, m);
        if (dot(wi, m) <= 0 || o.z <= 0) continue; // unlit, or reflected into the groove
        auto g1 = [&](const Vec3& v) { return std::min(1.0, 2 * m.z * v.z / dot(v, m)); };
        total += dot(wi, m) * std::min(g1(wi), g1(o)) / (2 * std::cos(beta) * wi.z);
    }
    return total;
}

double model_l1_albedo(double alpha, const Vec3& wi) {
    const Beckmann ndf(alpha);
    const MicrofacetModel model(ndf, FresnelTerm::mirror(), MaskingForm::height_correlated);
    return albedo_from_cells(model_cell_energy(model, wi, BeckersSensor(145), {}), 1)[0];
}
} // namespace

TEST_CASE("V-grooves at normal incidence: single-bounce escape is exactly 2 cos(2 beta)") {
    const BeckersSensor sensor(1000);
    const SpecularReflector mirror(FresnelTerm::mirror());
    for (double beta_deg : {32.0, 35.0, 40.0, 44.0}) {
        const double beta = radians(beta_deg);
        const Scene scene(v_grooves(beta, 64, 8));
        TraceSettings st;
        st.rays = 1 << 18;
        const TraceResult r = trace_incidence(scene, mirror, sensor, {0, 0, 1}, st);
        // V-cavity masking at i = n, o at 2 beta from the normal: G1 = 2 (n.m)(n.o) / (o.m)
        // = 2 cos(2 beta) (Torrance-Sparrow V-cavity G, M18 Eq. 15); the rest leaves after a second
        // bounce at 180 - 4 beta degrees, above the facets for beta < 45 degrees.
        const double expected = 2 * std::cos(2 * beta), n = double(r.rays);
        CAPTURE(beta_deg);
        CAPTURE(r.ledger.reflected[0]);
        // Each ray escapes or not by where it lands: a Bernoulli draw (the stratified beam only
        // makes the error smaller).
        CHECK(std::abs(r.ledger.reflected[0] - expected) <=
              4 * std::sqrt(expected * (1 - expected) / n) + 1e-9);
        CHECK(r.ledger.reflected[0] + r.ledger.reflected[1] == doctest::Approx(1.0).epsilon(1e-12));
        // Exits in the cells of the two mirror directions only.
        const Vec3 o1 = spherical_direction(2 * beta, 0.0), o2 = spherical_direction(2 * beta, kPi);
        const double single =
            r.energy[size_t(sensor.lookup(o1))] + r.energy[size_t(sensor.lookup(o2))];
        CHECK(single == doctest::Approx(r.ledger.reflected[0]).epsilon(1e-12));
    }
}

TEST_CASE("generated Beckmann 0.5: simulated L1 against the height-correlated Smith model") {
    const Beckmann target(0.5);
    SurfaceSpec spec;
    spec.size = 512;
    // The surface these findings were recorded on (the pool's path, 500 iterations). On the exact
    // marginal's default surface (100 iterations) the 60 deg gap is +0.0012 (tolerance 0.0007),
    // 0 deg +0.0096, 75 deg -0.0012: the same signs, the crossing moved past 60 deg; the gap
    // belongs to each surface's masking (docs/masking.md), not to Smith's alpha.
    spec.target = MatchTarget::pool;
    spec.iterations = 500;
    const HeightField surface = generate_surface(target, spec, 2);
    const SurfaceMetrics m = measure_surface(surface, target);
    // The surface's roughness, and how well it is known: the spread of its estimators (median
    // slope ratio and RMS slope, along x and y).
    const double estimates[] = {m.alpha_eff_x, m.alpha_eff_y, m.alpha_rms_x, m.alpha_rms_y};
    const double alpha_lo = *std::min_element(std::begin(estimates), std::end(estimates));
    const double alpha_hi = *std::max_element(std::begin(estimates), std::end(estimates));
    const double alpha = 0.5 * (alpha_lo + alpha_hi);
    CAPTURE(alpha_lo);
    CAPTURE(alpha_hi);
    const Scene scene(surface);
    const SpecularReflector mirror(FresnelTerm::mirror());
    TraceSettings st;
    st.rays = 1 << 22;
    st.orders = 1;
    auto compare = [&](double theta_deg, double& difference, double& tolerance) {
        const Vec3 wi = spherical_direction(radians(theta_deg), 0.0);
        const TraceResult r = trace_incidence(scene, mirror, BeckersSensor(145), wi, st);
        const double sim = r.ledger.reflected[0], model = model_l1_albedo(alpha, wi);
        // Monte Carlo: each ray's first exit is L1 or not (Bernoulli; stratification only helps).
        const double sigma = std::sqrt(sim * (1 - sim) / double(r.rays));
        // Roughness: the model's change over the surface's range of effective alpha.
        const double from_alpha =
            0.5 * std::abs(model_l1_albedo(alpha_hi, wi) - model_l1_albedo(alpha_lo, wi));
        difference = sim - model;
        tolerance = 4 * sigma + from_alpha;
        MESSAGE("theta_i " << theta_deg << ": simulated L1 " << sim << ", model " << model
                           << ", difference " << difference << ", tolerance " << tolerance);
    };
    double difference, tolerance;
    // At theta_i = 60 degrees the model and the simulation agree within the tolerance.
    compare(60.0, difference, tolerance);
    CHECK(std::abs(difference) <= tolerance);
    // Elsewhere Smith's model is off by more than the Monte Carlo error and the roughness
    // uncertainty explain, and the sign changes with the incidence: at normal incidence it
    // overestimates the masking of the reflected light ("Smith's GAF overestimates shadowing for
    // some directions", R19 section 5.2), so the simulated L1 is ~1 % higher (it would take alpha
    // ~ 0.485 to close); at 75 degrees it is ~0.15 % lower. The V-groove test above shows that
    // the simulator's single scattering is exact, so these are the model's gaps: recorded and
    // bounded here, reported by `gonio run` for any case.
    compare(0.0, difference, tolerance);
    CHECK(difference > tolerance);
    CHECK(difference < 0.02);
    compare(75.0, difference, tolerance);
    CHECK(difference < -tolerance);
    CHECK(difference > -0.005);
}

TEST_CASE("V-grooves at oblique incidence across the grooves: the exact V-cavity single bounce") {
    const BeckersSensor sensor(145);
    const SpecularReflector mirror(FresnelTerm::mirror());
    for (double beta_deg : {20.0, 35.0, 50.0, 65.0}) {
        const double beta = radians(beta_deg);
        const Scene scene(v_grooves(beta, 64, 8));
        for (double theta_deg : {30.0, 60.0, 80.0, 86.0, 89.0}) {
            const Vec3 wi = spherical_direction(radians(theta_deg), 0.0);
            TraceSettings st;
            st.rays = 1 << 18;
            const TraceResult r = trace_incidence(scene, mirror, sensor, wi, st);
            const double expected = std::min(1.0, v_groove_l1(beta, wi)), n = double(r.rays);
            CAPTURE(beta_deg);
            CAPTURE(theta_deg);
            CAPTURE(expected);
            CHECK(std::abs(r.ledger.reflected[0] - expected) <=
                  4 * std::sqrt(expected * (1 - expected) / n) + 1e-9);
            CHECK(r.ledger.lost[0] == 0.0);
        }
    }
}
