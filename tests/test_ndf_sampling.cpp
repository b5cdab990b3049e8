#include "chi_square_harness.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"

#include <doctest/doctest.h>
#include <memory>
#include <string>
#include <vector>

using namespace gonio;

namespace {
// 4 distributions x (D cos + visible normals at 3 angles) = 16 tests, Sidak-corrected at 1%.
constexpr int kTests = 16;
constexpr int kSamples = 1000000;
constexpr int kCells = 1501;

std::vector<std::unique_ptr<Ndf>> sampled_ndfs() {
    std::vector<std::unique_ptr<Ndf>> out;
    out.push_back(std::make_unique<Beckmann>(0.5, 0.5));
    out.push_back(std::make_unique<Beckmann>(0.1, 0.8));
    out.push_back(std::make_unique<Ggx>(0.5, 0.5));
    out.push_back(std::make_unique<Ggx>(0.1, 0.8));
    return out;
}

void check(const test::DirectionChiSquare& r, const std::string& what) {
    CAPTURE(what);
    CAPTURE(r.chi.statistic);
    CAPTURE(r.chi.dof);
    CAPTURE(r.chi.p_value);
    CAPTURE(r.chi.pooled_bins);
    CAPTURE(r.chi.failure);
    CHECK(r.chi.failure.empty());
    CHECK(std::abs(r.pdf_integral - 1.0) < 1e-4);
    CHECK(r.chi.p_value > sidak_level(0.01, kTests));
}
} // namespace

TEST_CASE("sampling D(m) cos(theta_m) passes a chi-square test") {
    std::uint64_t seed = 1;
    for (const auto& ndf : sampled_ndfs()) {
        const auto r = test::chi_square_directions(
            [&](double u1, double u2) { return ndf->sample_m(u1, u2); },
            [&](const Vec3& m) { return ndf->pdf_m(m); }, kSamples, kCells, seed++);
        check(r, ndf->describe() + " D cos");
    }
}

TEST_CASE("sampling visible normals passes a chi-square test") {
    std::uint64_t seed = 100;
    for (const auto& ndf : sampled_ndfs()) {
        for (double theta_deg : {0.0, 45.0, 85.0}) {
            const Vec3 v = spherical_direction(radians(theta_deg), radians(30.0));
            const auto r = test::chi_square_directions(
                [&](double u1, double u2) { return ndf->sample_visible(v, u1, u2); },
                [&](const Vec3& m) { return ndf->pdf_visible(v, m); }, kSamples, kCells, seed++);
            check(r, ndf->describe() + " visible from theta=" + std::to_string(theta_deg));
        }
    }
}

TEST_CASE("the chi-square harness rejects a wrong sampler") {
    // Power check: sampling Beckmann 0.5 against the pdf of Beckmann 0.55 must fail clearly.
    const Beckmann a(0.5), b(0.55);
    const auto r =
        test::chi_square_directions([&](double u1, double u2) { return a.sample_m(u1, u2); },
                                    [&](const Vec3& m) { return b.pdf_m(m); }, kSamples, kCells, 7);
    CHECK(r.chi.p_value < 1e-6);
}
