#include "core/hemisphere_integral.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"

#include <cmath>
#include <doctest/doctest.h>
#include <memory>
#include <vector>

using namespace gonio;
using gonio::hemisphere_integral;

namespace {
std::vector<std::unique_ptr<Ndf>> all_ndfs(const std::vector<std::pair<double, double>>& alphas) {
    std::vector<std::unique_ptr<Ndf>> out;
    for (auto [ax, ay] : alphas) {
        out.push_back(std::make_unique<Beckmann>(ax, ay));
        out.push_back(std::make_unique<Ggx>(ax, ay));
    }
    return out;
}
} // namespace

TEST_CASE("NDF normalisation: integral of D(m) cos(theta_m) is 1") {
    for (const auto& ndf :
         all_ndfs({{0.01, 0.01}, {0.1, 0.1}, {0.5, 0.5}, {1, 1}, {2, 2}, {0.1, 0.8}})) {
        CAPTURE(ndf->describe());
        const double integral = hemisphere_integral([&](const Vec3& m) { return ndf->D(m) * m.z; },
                                                    ndf->narrowest_feature());
        CHECK(std::abs(integral - 1.0) < 1e-4);
        CHECK(std::abs(integral - 1.0) < 1e-7); // in fact far better than the 1e-4 asked for
    }
}

TEST_CASE("D matches the closed forms of M18 Eq. 16 and Eq. 21 in angles") {
    const double ax = 0.3, ay = 0.7;
    const Beckmann beckmann(ax, ay);
    const Ggx ggx(ax, ay);
    for (double t : {0.0, 0.2, 0.7, 1.2, 1.5}) {
        for (double p : {0.0, 0.4, 1.9, 4.0}) {
            const Vec3 m = spherical_direction(t, p);
            const double t2 = std::tan(t) * std::tan(t), c4 = std::pow(std::cos(t), 4);
            const double e = t2 * (std::cos(p) * std::cos(p) / (ax * ax) +
                                   std::sin(p) * std::sin(p) / (ay * ay));
            CHECK(beckmann.D(m) ==
                  doctest::Approx(std::exp(-e) / (kPi * ax * ay * c4)).epsilon(1e-12));
            CHECK(ggx.D(m) ==
                  doctest::Approx(1 / (kPi * ax * ay * c4 * (1 + e) * (1 + e))).epsilon(1e-12));
        }
    }
}

TEST_CASE("Smith Lambda matches brute-force integration of R19 Eq. 5") {
    // 1 + Lambda(v) = integral <v.m> D(m) dw_m / cos(theta_v)   [R19 Eq. 5 and Eq. 8]
    for (const auto& ndf : all_ndfs({{0.1, 0.1}, {0.5, 0.5}, {1, 1}, {0.1, 0.8}})) {
        const bool aniso = ndf->narrowest_feature() != ndf->widest_feature();
        for (double theta_deg : {0.0, 30.0, 60.0, 85.0, 89.9}) {
            for (double phi_deg :
                 aniso ? std::vector<double>{0, 30, 90, 135} : std::vector<double>{20}) {
                const Vec3 v = spherical_direction(radians(theta_deg), radians(phi_deg));
                const double integral = hemisphere_integral(
                    [&](const Vec3& m) { return std::max(0.0, dot(v, m)) * ndf->D(m); },
                    ndf->narrowest_feature(), &v);
                const double brute = integral / v.z - 1.0;
                const double lambda = ndf->lambda(v);
                CAPTURE(ndf->describe());
                CAPTURE(theta_deg);
                CAPTURE(phi_deg);
                CAPTURE(lambda);
                CAPTURE(brute);
                CHECK(std::abs(brute - lambda) <= 1e-7 * (1 + lambda));
            }
        }
    }
}

TEST_CASE("visible normals are normalised: integral G1(v) D(m) <v.m> / cos(theta_v) = 1") {
    for (const auto& ndf : all_ndfs({{0.1, 0.1}, {0.5, 0.5}, {1, 1}, {0.1, 0.8}})) {
        for (double theta_deg : {0.0, 45.0, 85.0, 89.9}) {
            const Vec3 v = spherical_direction(radians(theta_deg), radians(30.0));
            const double integral =
                hemisphere_integral([&](const Vec3& m) { return ndf->pdf_visible(v, m); },
                                    ndf->narrowest_feature(), &v);
            CAPTURE(ndf->describe());
            CAPTURE(theta_deg);
            CHECK(std::abs(integral - 1.0) < 1e-7);
        }
    }
}

TEST_CASE("Smith terms: limits and ranges") {
    for (const auto& ndf : all_ndfs({{1e-4, 1e-4}, {0.5, 0.5}, {100, 100}, {0.01, 3}})) {
        CAPTURE(ndf->describe());
        CHECK(ndf->lambda({0, 0, 1}) == 0.0); // no masking at normal view
        CHECK(ndf->G1({0, 0, 1}) == 1.0);
        CHECK(ndf->G1({1, 0, 0}) == 0.0); // horizon: fully masked
        CHECK(ndf->G1({1, 0, -0.1}) == 0.0);
        double previous = -1;
        for (double t = 0; t < kPi / 2; t += 0.05) { // Lambda grows towards grazing
            const double l = ndf->lambda(spherical_direction(t, 0.3));
            CHECK(std::isfinite(l));
            CHECK(l >= previous);
            previous = l;
        }
        const double grazing = ndf->lambda(spherical_direction(radians(89.9999), 0.0));
        CHECK(std::isfinite(grazing));
        // D is finite and non-negative everywhere, including at the horizon.
        for (double t : {0.0, 1e-8, 0.5, 1.5, kPi / 2 - 1e-12, kPi / 2}) {
            const double d = ndf->D(spherical_direction(t, 0.7));
            CHECK(std::isfinite(d));
            CHECK(d >= 0);
        }
        const Vec3 i = spherical_direction(0.3, 0), o = spherical_direction(1.2, 2.0);
        const Vec3 h = normalize(i + o);
        const double hc = ndf->G2(i, o, h, MaskingForm::height_correlated);
        const double un = ndf->G2(i, o, h, MaskingForm::uncorrelated);
        CHECK(hc >= un); // 1/(1+a+b) >= 1/((1+a)(1+b))
        CHECK(hc <= 1.0);
        CHECK(ndf->G2(i, o, -h, MaskingForm::height_correlated) == 0.0); // back-facing
    }
}
