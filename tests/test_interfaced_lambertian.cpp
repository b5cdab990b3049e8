// The interfaced Lambertian facet [M18 section 3.1]: its diffuse interface reflectances, its
// energy balance ray by ray, its directional albedo and the distribution of its body exits.
#include "chi_square_harness.h"
#include "gonio/material/fresnel.h"
#include "gonio/material/interfaced_lambertian.h"

#include <cmath>
#include <doctest/doctest.h>

using namespace gonio;

TEST_CASE("interfaced Lambertian: r_e by quadrature is Molenaar's closed form [M18 Eq. 11]") {
    for (double n : {1.05, 1.2, 1.33, 1.5, 2.0, 3.0}) {
        CAPTURE(n);
        CHECK(InterfacedLambertianFacet::diffuse_reflectance(n) ==
              doctest::Approx(InterfacedLambertianFacet::molenaar_reflectance(n)).epsilon(1e-9));
    }
    CHECK(InterfacedLambertianFacet::diffuse_reflectance(1.0) == 0.0);
    // Just above 1, where Eq. 11's terms cancel, the quadrature stays smooth: r_e grows linearly
    // in n - 1 (the grazing Fresnel rise, whose width shrinks with n - 1).
    const double near = InterfacedLambertianFacet::diffuse_reflectance(1 + 1e-6);
    CHECK(near > 0);
    CHECK(near < 1e-6);
    CHECK(InterfacedLambertianFacet::diffuse_reflectance(1 + 2e-6) ==
          doctest::Approx(2 * near).epsilon(0.01));
    const InterfacedLambertianFacet il({1.5}, {0.6});
    CHECK(1.5 * 1.5 * (1 - il.internal_diffuse_reflectance(0)) ==
          doctest::Approx(1 - il.external_diffuse_reflectance(0)).epsilon(1e-12));
}

TEST_CASE("interfaced Lambertian: with K_d = 1 every ray leaves with its whole weight") {
    const InterfacedLambertianFacet il({1.5}, {1.0});
    Rng rng{1};
    const Vec3 m = normalize(Vec3{0.3, -0.2, 1.0});
    for (int k = 0; k < 20000; ++k) {
        const Vec3 wi = normalize(Vec3{rng.uniform() - 0.5, rng.uniform() - 0.5, 1.0});
        double w = 1;
        Vec3 wo;
        REQUIRE(il.scatter(wi, m, rng, wo, &w));
        CHECK(w == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(dot(wo, m) > 0);
    }
}

TEST_CASE("interfaced Lambertian: mean weight is the facet albedo, per channel") {
    // Two channels of different index (n = 1 is a plain Lambertian facet) and albedo.
    const InterfacedLambertianFacet il({1.0, 1.5}, {0.6, 0.3});
    const Vec3 m{0, 0, 1};
    for (double theta : {0.0, 1.0, 1.4}) {
        const Vec3 wi = spherical_direction(theta, 0.3);
        Rng rng{2, std::uint64_t(theta * 100)};
        const int n = 200000;
        double sum[2] = {0, 0}, sum2[2] = {0, 0};
        for (int k = 0; k < n; ++k) {
            double w[2] = {1, 1};
            Vec3 wo;
            il.scatter(wi, m, rng, wo, w);
            for (int c = 0; c < 2; ++c) sum[c] += w[c], sum2[c] += w[c] * w[c];
        }
        for (int c = 0; c < 2; ++c) {
            const double mean = sum[c] / n, sigma = std::sqrt((sum2[c] / n - mean * mean) / n);
            CAPTURE(theta);
            CAPTURE(c);
            CHECK(std::abs(mean - il.albedo(wi, m, c)) <= 4 * sigma + 1e-12);
        }
    }
    CHECK(il.albedo(spherical_direction(0.5, 0), m, 0) == doctest::Approx(0.6)); // n = 1: K_d
}

TEST_CASE("interfaced Lambertian: the body's exits follow T(o) cos [M18 Eq. 9]") {
    const InterfacedLambertianFacet il({1.5}, {0.8});
    const Vec3 m{0, 0, 1}, wi = spherical_direction(0.7, 1.0);
    const Vec3 mirror = 2 * dot(wi, m) * m - wi;
    Rng rng{3};
    // Body exits only (the specular ones go exactly to the mirror direction).
    auto body_exit = [&](double, double) {
        for (;;) {
            double w = 1;
            Vec3 wo;
            il.scatter(wi, m, rng, wo, &w);
            if (dot(wo, mirror) < 1 - 1e-12) return wo;
        }
    };
    const double re = il.external_diffuse_reflectance(0);
    const auto r = test::chi_square_directions(
        body_exit,
        [&](const Vec3& o) {
            return o.z > 0 ? (1 - fresnel_dielectric(o.z, 1.5)) * o.z / (kPi * (1 - re)) : 0.0;
        },
        200000, 577, 11);
    CAPTURE(r.chi.p_value);
    CHECK(r.chi.failure.empty());
    CHECK(r.chi.p_value > 0.01);
    CHECK(r.pdf_integral == doctest::Approx(1.0).epsilon(1e-5));
    // And the body BRDF integrates to the body albedo: int f_b cos = T(i) K_d (1 - r_i) / (1 - K_d
    // r_i).
    double integral = 0;
    const int steps = 400;
    for (int a = 0; a < steps; ++a)
        for (int b = 0; b < steps; ++b) {
            const double t = 0.5 * kPi * (a + 0.5) / steps, p = kTwoPi * (b + 0.5) / steps;
            const Vec3 o = spherical_direction(t, p);
            integral += il.body_brdf(wi, o, m, 0) * o.z * std::sin(t) * (0.5 * kPi / steps) *
                        (kTwoPi / steps);
        }
    const double ti = 1 - fresnel_dielectric(dot(wi, m), 1.5),
                 ri = il.internal_diffuse_reflectance(0);
    CHECK(integral == doctest::Approx(ti * 0.8 * (1 - ri) / (1 - 0.8 * ri)).epsilon(1e-4));
}
