// The tabulated BSDF (gonio/table): the sensor interpolant's exact integral and sampler, energy
// kept at every node, rotation of isotropic sweeps, phi_i wrapping of anisotropic ones, and the
// sampler of the whole table against its pdf (chi-square).
#include "chi_square_harness.h"
#include "gonio/table/bsdf_table.h"
#include "gonio/table/sensor_lobe.h"

#include <algorithm>
#include <doctest/doctest.h>
#include <stdexcept>

using namespace gonio;

namespace {
constexpr int kChiTests = 4; // chi-square tests in this file (Sidak)

Vec3 rotate_z(const Vec3& v, double a) {
    return {std::cos(a) * v.x - std::sin(a) * v.y, std::sin(a) * v.x + std::cos(a) * v.y, v.z};
}

// A smooth glossy lobe around the mirror direction of wi plus a diffuse floor, 1/sr.
double glossy(const Vec3& wi, const Vec3& wo) {
    const Vec3 r{-wi.x, -wi.y, wi.z};
    return 0.1 + 2.0 * std::exp(8.0 * (dot(r, wo) - 1));
}

// A table of `glossy` sampled at the cell centres of a sweep.
TableData glossy_table(std::vector<double> theta, std::vector<double> phi, int cells,
                       bool isotropic, int channels = 2) {
    TableData d;
    d.theta_i_deg = theta;
    d.phi_i_deg = phi;
    d.cells = cells;
    d.channels = channels;
    d.isotropic = isotropic;
    const BeckersSensor sensor(cells);
    for (double t : theta)
        for (double p : phi) {
            const Vec3 wi = spherical_direction(radians(t), radians(p));
            for (int c = 0; c < cells; ++c)
                for (int ch = 0; ch < channels; ++ch)
                    d.f.push_back((1.0 + 0.5 * ch) * glossy(wi, sensor.cell(c).center));
        }
    return d;
}
} // namespace

TEST_CASE("sensor lobe: the interpolant's integral is exact (against a fine midpoint rule)") {
    const BeckersSensor sensor(400);
    const SensorLobeGrid grid(sensor);
    Rng rng{7, 1};
    std::vector<double> v(size_t(sensor.cell_count()));
    for (double& x : v) x = rng.uniform();
    const SensorLobeSampler lobe(grid, v);
    // cos theta dw = ds dphi / 2 with s = sin^2 theta.
    const int ns = 3000, nphi = 3000;
    double sum = 0;
    for (int i = 0; i < ns; ++i) {
        const double s = (i + 0.5) / ns, r = std::sqrt(s), z = std::sqrt(1 - s);
        for (int j = 0; j < nphi; ++j) {
            const double phi = kTwoPi * (j + 0.5) / nphi;
            sum += lobe.eval({r * std::cos(phi), r * std::sin(phi), z});
        }
    }
    sum *= 0.5 * (1.0 / ns) * (kTwoPi / nphi);
    CHECK(grid.integral(v.data()) == doctest::Approx(lobe.total()).epsilon(1e-12));
    CHECK(sum == doctest::Approx(lobe.total()).epsilon(2e-5));
}

TEST_CASE("sensor lobe: interpolation passes through every cell centre") {
    const BeckersSensor sensor(1000);
    const SensorLobeGrid grid(sensor);
    Rng rng{8, 1};
    std::vector<double> v(size_t(sensor.cell_count()));
    for (double& x : v) x = rng.uniform();
    const SensorLobeSampler lobe(grid, v);
    for (int c = 0; c < sensor.cell_count(); ++c)
        REQUIRE(lobe.eval(sensor.cell(c).center) == doctest::Approx(v[c]).epsilon(1e-9));
}

TEST_CASE("sensor lobe: samples follow eval cos / total (chi-square)") {
    const BeckersSensor sensor(900);
    const SensorLobeGrid grid(sensor);
    std::vector<double> v;
    for (const SensorCell& c : sensor.cells()) // a peaked lobe with an empty region
        v.push_back(c.center.x > 0.3 ? 0.0 : std::exp(6 * (c.center.z - 1)) + 0.05);
    const SensorLobeSampler lobe(grid, v);
    Rng extra{9, 2};
    const auto r = test::chi_square_directions(
        [&](double a, double b) { return lobe.sample(extra.uniform(), a, b); },
        [&](const Vec3& d) { return lobe.pdf(d); }, 400000, 1600, 11);
    CHECK(r.chi.failure == "");
    CHECK(r.pdf_integral == doctest::Approx(1.0).epsilon(1e-3));
    CHECK(r.chi.p_value > sidak_level(0.01, kChiTests));
}

TEST_CASE("bsdf table: a constant (Lambertian) table is constant everywhere") {
    TableData d;
    d.theta_i_deg = {0, 40, 80};
    d.phi_i_deg = {0};
    d.cells = 600;
    d.channels = 1;
    d.f.assign(3 * 600, 0.7 / kPi);
    const BsdfTable table(d);
    Rng rng{3, 3};
    for (int k = 0; k < 2000; ++k) {
        const Vec3 wi = spherical_direction(std::acos(rng.uniform()), kTwoPi * rng.uniform());
        const Vec3 wo = spherical_direction(std::acos(rng.uniform()), kTwoPi * rng.uniform());
        double f = 0;
        table.eval(wi, wo, &f);
        REQUIRE(f == doctest::Approx(0.7 / kPi).epsilon(1e-12));
    }
    double a = 0;
    table.albedo(spherical_direction(0.3, 1.0), &a);
    CHECK(a == doctest::Approx(0.7).epsilon(1e-12));
}

TEST_CASE("bsdf table: each node keeps the table's albedo, between nodes it is linear") {
    const BsdfTable table(glossy_table({0, 20, 40, 60}, {0}, 1200, true));
    for (int ti = 0; ti < 4; ++ti)
        for (int ch = 0; ch < 2; ++ch) {
            double sum = 0; // the table's own sum_c f_c Omega_perp_c
            const auto& d = table.data();
            for (int c = 0; c < d.cells; ++c)
                sum += d.f[(size_t(ti) * d.cells + c) * 2 + ch] *
                       table.sensor().cell(c).projected_solid_angle;
            double a[2];
            table.albedo(spherical_direction(radians(table.theta_nodes()[ti]), 0.4), a);
            CHECK(a[ch] == doctest::Approx(sum).epsilon(1e-12));
            CHECK(table.node_albedo(ti, 0, ch) == doctest::Approx(sum).epsilon(1e-12));
            // The interpolated lobe integrated by brute force holds the same energy.
            const Vec3 wi = spherical_direction(radians(table.theta_nodes()[ti]), 0.4);
            double brute = 0;
            const int n = 600;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    const double s = (i + 0.5) / n, phi = kTwoPi * (j + 0.5) / n;
                    double f[2];
                    table.eval(wi,
                               {std::sqrt(s) * std::cos(phi), std::sqrt(s) * std::sin(phi),
                                std::sqrt(1 - s)},
                               f);
                    brute += f[ch];
                }
            brute *= 0.5 * kTwoPi / (double(n) * n);
            CHECK(brute == doctest::Approx(sum).epsilon(2e-3));
        }
    double a30[2];
    table.albedo(spherical_direction(radians(30), 0), a30);
    CHECK(a30[1] == doctest::Approx(0.5 * (table.node_albedo(1, 0, 1) + table.node_albedo(2, 0, 1)))
                        .epsilon(1e-12));
}

TEST_CASE("bsdf table: an isotropic sweep at phi_i = 0 is rotated to any azimuth") {
    const BsdfTable table(glossy_table({0, 15, 30, 45, 60, 75}, {0}, 2000, true));
    Rng rng{5, 1};
    for (int k = 0; k < 500; ++k) {
        const Vec3 wi = spherical_direction(radians(75 * rng.uniform()), kTwoPi * rng.uniform());
        const Vec3 wo = spherical_direction(std::acos(rng.uniform()), kTwoPi * rng.uniform());
        const double a = kTwoPi * rng.uniform();
        double f1[2], f2[2];
        table.eval(wi, wo, f1);
        table.eval(rotate_z(wi, a), rotate_z(wo, a), f2);
        REQUIRE(f2[0] == doctest::Approx(f1[0]).epsilon(1e-9));
    }
    // At a swept incidence the lobe is close to the smooth function it tabulates.
    const Vec3 wi = spherical_direction(radians(30), 1.2);
    // Linear interpolation between centres ~3.2 deg apart of a lobe of ~20 deg: errors of the
    // order of (h / width)^2 / 8 relative, largest on the peak, where curvature is.
    std::vector<double> error;
    for (int k = 0; k < 501; ++k) {
        const Vec3 wo = spherical_direction(std::acos(rng.uniform()), kTwoPi * rng.uniform());
        double f[2];
        table.eval(wi, wo, f);
        error.push_back(std::abs(f[0] / glossy(wi, wo) - 1));
    }
    std::sort(error.begin(), error.end());
    MESSAGE("median " << error[250] << ", worst " << error.back());
    CHECK(error[250] < 0.01);
    CHECK(error.back() < 0.1);
}

TEST_CASE("bsdf table: an anisotropic sweep wraps in phi_i, a partial turn is refused") {
    TableData d;
    d.theta_i_deg = {30};
    d.phi_i_deg = {0, 90, 180, 270};
    d.cells = 300;
    d.isotropic = false;
    for (int j = 0; j < 4; ++j) d.f.insert(d.f.end(), 300, 0.1 * (j + 1));
    const BsdfTable table(d);
    double f = 0;
    table.eval(spherical_direction(radians(30), radians(315)), {0, 0, 1}, &f);
    CHECK(f == doctest::Approx(0.5 * (0.4 + 0.1)).epsilon(1e-12));
    table.eval(spherical_direction(radians(30), radians(45)), {0, 0, 1}, &f);
    CHECK(f == doctest::Approx(0.15).epsilon(1e-12));
    table.eval(spherical_direction(radians(30), radians(-10)), {0, 0, 1}, &f);
    CHECK(f == doctest::Approx(0.4 + (0.1 - 0.4) * 80.0 / 90.0).epsilon(1e-12));

    d.phi_i_deg = {0, 45};
    d.f.resize(600);
    CHECK_THROWS_WITH_AS(BsdfTable{d}, doctest::Contains("full turn"), std::invalid_argument);
}

TEST_CASE("bsdf table: samples between swept incidences follow the pdf (chi-square)") {
    const BsdfTable table(glossy_table({0, 20, 40, 60, 80}, {0}, 1500, true, 1));
    const Vec3 wi = spherical_direction(radians(47), radians(33));
    Rng extra{12, 3};
    const auto r = test::chi_square_directions(
        [&](double a, double b) {
            BsdfTable::Sample s;
            return table.sample(wi, extra.uniform(), a, b, s) ? s.wo : Vec3{0, 0, -1};
        },
        [&](const Vec3& d) { return table.pdf(wi, d); }, 400000, 1600, 13);
    CHECK(r.chi.failure == "");
    CHECK(r.pdf_integral == doctest::Approx(1.0).epsilon(1e-3));
    CHECK(r.chi.p_value > sidak_level(0.01, kChiTests));
    // The pdf is the sampling scalar times cos over the albedo.
    double a = 0;
    table.albedo(wi, &a);
    const Vec3 wo = spherical_direction(0.4, 2.0);
    CHECK(table.pdf(wi, wo) == doctest::Approx(table.eval_mean(wi, wo) * wo.z / a).epsilon(1e-9));
}

TEST_CASE("bsdf table: a transmission table lives on the lower hemisphere") {
    TableData d = glossy_table({0, 45}, {0}, 500, true, 1);
    d.transmission = true;
    const BsdfTable table(d);
    double f = 0;
    table.eval(spherical_direction(0.3, 0), {0, 0, 1}, &f);
    CHECK(f == 0);
    table.eval(spherical_direction(0.3, 0), {0, 0, -1}, &f);
    CHECK(f > 0);
    BsdfTable::Sample s;
    Rng rng{1, 1};
    for (int k = 0; k < 100; ++k) {
        REQUIRE(table.sample(spherical_direction(0.3, 0), rng.uniform(), rng.uniform(),
                             rng.uniform(), s));
        REQUIRE(s.wo.z < 0);
    }
}
