#include "core/chi_square.h"
#include "core/random.h"
#include "sensor/beckers_sensor.h"

#include <cmath>
#include <doctest/doctest.h>
#include <vector>

using namespace gonio;

TEST_CASE("every Beckers cell subtends 2 pi / N") {
    for (int n : {1, 2, 3, 7, 145, 3240, 10000}) {
        CAPTURE(n);
        const BeckersSensor s(n);
        REQUIRE(s.cell_count() == n);
        REQUIRE(static_cast<int>(s.cells().size()) == n);
        double total = 0, projected = 0;
        for (const SensorCell& c : s.cells()) {
            CHECK(std::abs(c.solid_angle - kTwoPi / n) < 1e-12);
            // The same area from the cell's angular bounds, independently of the stored value.
            const double from_bounds =
                (std::cos(c.theta_min) - std::cos(c.theta_max)) * (c.phi_max - c.phi_min);
            CHECK(std::abs(from_bounds - kTwoPi / n) < 1e-12);
            total += c.solid_angle;
            projected += c.projected_solid_angle;
        }
        CHECK(total == doctest::Approx(kTwoPi).epsilon(1e-12));
        CHECK(projected ==
              doctest::Approx(kPi).epsilon(1e-12)); // integral of cos over the hemisphere
    }
}

TEST_CASE("Beckers rings tile the hemisphere from the pole to the horizon") {
    for (int n : {1, 2, 145, 3240, 10000}) {
        CAPTURE(n);
        const BeckersSensor s(n);
        CHECK(s.cell(0).theta_min == 0.0);
        CHECK(s.cell(n - 1).theta_max == doctest::Approx(kPi / 2).epsilon(1e-15));
        for (int r = 0; r + 1 < s.ring_count(); ++r)
            CHECK(s.cell(s.ring_first_cell(r)).theta_max ==
                  s.cell(s.ring_first_cell(r + 1)).theta_min);
        if (n > 1) CHECK(s.ring_cell_count(0) == 1); // one polar cell
    }
}

TEST_CASE("Beckers cells of the shipped sizes are close to square") {
    // Some N give a poor second ring (docs/architecture.md). Polar extent over azimuthal
    // width, for every ring outside the polar cap.
    for (int n : {145, 3240, 10000}) {
        const BeckersSensor s(n);
        double worst = 1;
        for (int r = 1; r < s.ring_count(); ++r) {
            const double a = s.ring_aspect_ratio(r);
            worst = std::max(worst, std::max(a, 1 / a));
        }
        CAPTURE(n);
        CAPTURE(worst);
        CHECK(worst < 1.6);
    }
}

TEST_CASE("uniform directions fill the Beckers cells uniformly (chi-square)") {
    const int samples = 1000000;
    for (int n : {145, 3240}) {
        const BeckersSensor s(n);
        std::vector<double> observed(n, 0.0), expected(n, static_cast<double>(samples) / n);
        Rng rng{2024, static_cast<std::uint64_t>(n)};
        for (int k = 0; k < samples; ++k) {
            const double z = rng.uniform(), phi = kTwoPi * rng.uniform();
            const double r = std::sqrt(1 - z * z);
            observed[s.lookup({r * std::cos(phi), r * std::sin(phi), z})] += 1;
        }
        const ChiSquareResult chi = chi_square_test(observed, expected);
        CAPTURE(n);
        CAPTURE(chi.statistic);
        CAPTURE(chi.dof);
        CHECK(chi.failure.empty());
        CHECK(chi.p_value > sidak_level(0.01, 2));
    }
}

TEST_CASE("Beckers lookup: edge cases land in valid cells") {
    for (int n : {1, 2, 145, 3240, 10000}) {
        CAPTURE(n);
        const BeckersSensor s(n);
        CHECK(s.lookup({0, 0, 1}) == 0); // theta = 0
        for (double phi : {0.0, kPi / 3, kPi, kTwoPi, std::nextafter(kTwoPi, 0.0)}) {
            const int horizon = s.lookup({std::cos(phi), std::sin(phi), 0.0}); // theta = 90 deg
            CHECK(horizon >= 0);
            CHECK(horizon < n);
            CHECK(s.cell(horizon).ring == s.ring_count() - 1);
        }
        // phi = 0 and phi = 2 pi (after round-off, y = -0 or a tiny negative) are the same cell.
        const double r = std::sin(1.0), z = std::cos(1.0);
        CHECK(s.lookup({r, 0.0, z}) == s.lookup({r, -0.0, z}));
        CHECK(s.lookup({r, -1e-300, z}) ==
              s.lookup({r, 0.0, z}) + s.ring_cell_count(s.cell(s.lookup({r, 0.0, z})).ring) - 1);
        // Exactly on a ring boundary cos(theta) = 1 - S/N: the cell just outside the cap.
        for (int ring = 1; ring < s.ring_count(); ++ring) {
            const double zb = 1.0 - static_cast<double>(s.ring_first_cell(ring)) / n;
            const double rb = std::sqrt(1 - zb * zb);
            const int c = s.lookup({rb, 0.0, zb});
            CHECK(c >= 0);
            CHECK(c < n);
            CHECK(std::abs(s.cell(c).ring - ring) <= 1);
        }
        // Below the horizon is clamped to the horizon ring rather than out of range.
        CHECK(s.lookup({1, 0, -0.5}) < n);
    }
}

TEST_CASE("Beckers cell geometry round-trips through lookup, above and below") {
    for (int n : {1, 2, 145, 3240, 10000}) {
        CAPTURE(n);
        const BeckersSensor s(n);
        int mismatches = 0, mismatches_lower = 0;
        for (int c = 0; c < n; ++c) {
            const Vec3 d = s.cell(c).center;
            mismatches += s.lookup(d) != c;
            mismatches_lower += s.lookup_lower({d.x, d.y, -d.z}) != c;
            CHECK(s.cell(c).theta_center >= s.cell(c).theta_min);
            CHECK(s.cell(c).theta_center <= s.cell(c).theta_max);
        }
        CHECK(mismatches == 0);
        CHECK(mismatches_lower == 0);
    }
}

TEST_CASE("Beckers lookup agrees with the cell bounds (trigonometric reference) everywhere") {
    // The lookup estimates the azimuth with a polynomial and corrects the cell by exact side
    // tests; the reference is atan2 against the cells' phi bounds and acos against theta bounds.
    Rng rng{17, 0};
    for (int n : {3, 7, 145, 3240, 10000, 250000}) {
        CAPTURE(n);
        const BeckersSensor s(n);
        int outside = 0;
        auto check = [&](const Vec3& d, double slack) {
            const SensorCell& c = s.cell(s.lookup(d));
            const double theta = spherical_theta(d), phi = spherical_phi(d);
            const bool in_theta = theta >= c.theta_min - slack && theta <= c.theta_max + slack;
            const bool in_phi = (phi >= c.phi_min - slack && phi <= c.phi_max + slack) ||
                                (c.phi_min == 0 && phi >= kTwoPi - slack);
            outside += !(in_theta && in_phi);
        };
        for (int k = 0; k < 200000; ++k) {
            const double z = rng.uniform(), phi = kTwoPi * rng.uniform();
            const double r = std::sqrt(1 - z * z);
            check({r * std::cos(phi), r * std::sin(phi), z}, 1e-12);
        }
        // On and within a hair of every azimuthal boundary, at the ring's mid polar angle.
        for (const SensorCell& c : s.cells())
            for (double dphi : {-1e-9, 0.0, 1e-9}) {
                const double z = std::cos(0.5 * (c.theta_min + c.theta_max)),
                             r = std::sqrt(1 - z * z), phi = c.phi_min + dphi;
                check({r * std::cos(phi), r * std::sin(phi), z}, 1e-12);
            }
        CHECK(outside == 0);
    }
}
