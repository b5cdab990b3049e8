// The anisotropic blend [R19 Eq. 10] and mixtures: their reductions to a single distribution, the
// azimuth inversion of R19 Eq. 16, and the errors for inputs outside their definitions. (Both are
// also in the NDF battery of test_ndf_families.cpp.)
#include "core/config_error.h"
#include "gonio/config/config.h"
#include "heightfield/ndf/anisotropic_blend.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/ndf/mixture_ndf.h"
#include "heightfield/ndf/sinc_ndf.h"
#include "heightfield/ndf/student_t.h"

#include <cmath>
#include <doctest/doctest.h>
#include <memory>
#include <stdexcept>

using namespace gonio;

namespace {
void check_same(const Ndf& a, const Ndf& b, double d_tol, double lambda_tol) {
    for (double t : {0.0, 0.3, 0.8, 1.2, 1.5, 1.5707}) {
        for (double p : {0.0, 0.4, 1.1, 2.0, 4.0}) {
            const Vec3 d = spherical_direction(t, p);
            CAPTURE(t);
            CAPTURE(p);
            CHECK(std::abs(a.D(d) - b.D(d)) <= d_tol * (1 + b.D(d)));
            CHECK(std::abs(a.lambda(d) - b.lambda(d)) <= lambda_tol * (1 + b.lambda(d)));
        }
    }
}
} // namespace

TEST_CASE("a blend of one curve with itself is that curve") {
    for (int which = 0; which < 2; ++which) {
        auto make = [&]() -> std::unique_ptr<Ndf> {
            if (which == 0) return std::make_unique<SincNdf>(6.0, 0.05, 128);
            return std::make_unique<Ggx>(0.4, 0.4);
        };
        const auto iso = make();
        const AnisotropicBlend blend(make(), make());
        CAPTURE(iso->describe());
        check_same(blend, *iso, 1e-12, 1e-6);
        // Eq. 16 is uniform for equal curves, and each sample's theta is the curve's.
        for (double u : {0.0, 0.13, 0.5, 0.77, 0.999})
            CHECK(blend.sample_phi(u) == doctest::Approx(kTwoPi * u).epsilon(1e-12));
    }
}

TEST_CASE("the blend's azimuth sampling inverts R19 Eq. 16") {
    const AnisotropicBlend blend(std::make_unique<Ggx>(0.2, 0.2), std::make_unique<Beckmann>(0.6));
    const double dx = Ggx(0.2, 0.2).D({0, 0, 1}), dy = Beckmann(0.6).D({0, 0, 1});
    const double kappa = (dy - dx) / (4 * kPi * (dy + dx));
    for (int i = 0; i <= 100; ++i) {
        const double u = std::min(i / 100.0, 1 - 1e-16), phi = blend.sample_phi(u);
        CHECK(phi / kTwoPi + kappa * std::sin(2 * phi) == doctest::Approx(u).epsilon(1e-12));
    }
}

TEST_CASE("the blend's lobes lie along its axes") {
    const Ggx ggx(0.5, 0.5);
    const Beckmann beckmann(0.2);
    const AnisotropicBlend blend(std::make_unique<Ggx>(0.5, 0.5), std::make_unique<Beckmann>(0.2));
    const double c = 0.5 * (ggx.D({0, 0, 1}) + beckmann.D({0, 0, 1}));
    for (double t : {0.1, 0.6, 1.2}) { // R19 Eq. 10 at phi = 0 and pi/2
        CHECK(blend.D(spherical_direction(t, 0)) ==
              doctest::Approx(ggx.D(spherical_direction(t, 0)) * beckmann.D({0, 0, 1}) / c));
        CHECK(blend.D(spherical_direction(t, 0.5 * kPi)) ==
              doctest::Approx(beckmann.D(spherical_direction(t, 0)) * ggx.D({0, 0, 1}) / c));
    }
}

TEST_CASE("a mixture of two identical distributions is that distribution") {
    std::vector<std::unique_ptr<Ndf>> parts;
    parts.push_back(std::make_unique<StudentT>(0.3, 0.6, 3.0));
    parts.push_back(std::make_unique<StudentT>(0.3, 0.6, 3.0));
    const MixtureNdf mix(std::move(parts), {0.2, 0.6});
    const StudentT single(0.3, 0.6, 3.0);
    check_same(mix, single, 1e-12, 1e-12);
    CHECK(mix.weights()[0] == doctest::Approx(0.25));
}

TEST_CASE("blends and mixtures reject what they cannot represent") {
    CHECK_THROWS_WITH_AS(
        AnisotropicBlend(std::make_unique<Ggx>(0.2, 0.5), std::make_unique<Beckmann>(0.3)),
        doctest::Contains("must be isotropic"), std::invalid_argument);
    // A mixture's weights and components are user input: checked where the config is read.
    const std::string head = "[beam]\ntheta_i = 0\n[ndf]\ntype = \"mixture\"\n"
                             "components = [{ type = \"beckmann\", alpha = 0.3 }]\n";
    CHECK_THROWS_WITH_AS(parse_config(head + "weights = [0.0]\n", "m.toml"),
                         doctest::Contains("ndf.weights"), ConfigError);
    CHECK_THROWS_WITH_AS(parse_config(head + "weights = [0.5, 0.5]\n", "m.toml"),
                         doctest::Contains("ndf.weights"), ConfigError);
}
