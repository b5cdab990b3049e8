// Chermain et al.'s P-BRDF [C19]: the mixture of non-centred Beckmann lobes of a normal map.
#include "core/hemisphere_integral.h"
#include "gonio/model/microfacet_model.h"
#include "gonio/model/pbrdf_model.h"
#include "heightfield/exr_io.h"
#include "heightfield/generate.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/surface_generator.h"
#include "sensor/beckers_sensor.h"
#include "sensor/cell_integral.h"

#include <doctest/doctest.h>
#include <filesystem>

using namespace gonio;

namespace {
HeightField brushed_surface(int n) {
    SurfaceSpec spec;
    spec.size = n;
    spec.iterations = 50;
    return generate_surface(Beckmann(0.1, 0.4), spec, 2);
}
} // namespace

TEST_CASE("C19: one Beckmann lobe everywhere gives Beckmann's D, Lambda and BRDF") {
    for (auto [ax, ay] : {std::pair{0.3, 0.3}, {0.2, 0.6}}) {
        CAPTURE(ax);
        CAPTURE(ay);
        const Beckmann beckmann(ax, ay);
        const SlopeLobe lobe{0, 0, ax * ax / 2, ay * ay / 2, 0}; // Beckmann's slope variance
        const PBrdfModel p(std::vector<SlopeLobe>(7, lobe), FresnelTerm::mirror());
        const MicrofacetModel smith(beckmann, FresnelTerm::mirror(), MaskingForm::uncorrelated);
        for (double t : {0.0, 25.0, 60.0, 85.0})
            for (double f : {0.0, 50.0, 130.0}) {
                const Vec3 v = spherical_direction(radians(t), radians(f));
                CHECK(p.D(v) == doctest::Approx(beckmann.D(v)).epsilon(1e-12));
                CHECK(p.lambda(v) + 1 == doctest::Approx(beckmann.lambda(v) + 1).epsilon(1e-9));
                CHECK(p.projected_area(v) == doctest::Approx(v.z).epsilon(1e-14));
                const Vec3 o = spherical_direction(radians(40.0), radians(f + 150));
                double a = 0, b = 0;
                p.eval(v, o, &a);
                smith.eval(v, o, &b);
                CHECK(a == doctest::Approx(b).epsilon(2e-4)); // the G1 table's interpolation
            }
    }
}

TEST_CASE(
    "C19: the fitted mixture keeps the map's slope moments, and its P-NDF integrates to A_P") {
    const HeightField s = brushed_surface(16);
    const std::vector<SlopeLobe> lobes = fit_slope_lobes(s);
    REQUIRE(lobes.size() == 256);
    // The weights k_i form a partition of unity over the texels: the mixture's mean and second
    // moments are the map's, up to the sigma_eps floor (0.01^2 at most).
    double mp = 0, mq = 0, mpp = 0, mqq = 0, fp = 0, fq = 0, fpp = 0, fqq = 0;
    for (int y = 0; y < s.n; ++y)
        for (int x = 0; x < s.n; ++x)
            mp += s.p(x, y), mq += s.q(x, y), mpp += s.p(x, y) * s.p(x, y),
                mqq += s.q(x, y) * s.q(x, y);
    for (const SlopeLobe& l : lobes)
        fp += l.mx, fq += l.my, fpp += l.sxx + l.mx * l.mx, fqq += l.syy + l.my * l.my;
    const double a = double(lobes.size());
    CHECK(fp / a == doctest::Approx(mp / a).epsilon(1e-9));
    CHECK(fq / a == doctest::Approx(mq / a).epsilon(1e-9));
    CHECK(fpp / a - mpp / a >= -1e-12);
    CHECK(fpp / a - mpp / a <= 1e-4);
    CHECK(fqq / a - mqq / a >= -1e-12);
    CHECK(fqq / a - mqq / a <= 1e-4);
    const PBrdfModel p(lobes, FresnelTerm::mirror());
    CHECK(hemisphere_integral([&](const Vec3& m) { return p.D(m) * m.z; }, 0.02, nullptr, 1e-8) ==
          doctest::Approx(1.0).epsilon(1e-5));
    for (double t : {30.0, 70.0}) {
        CAPTURE(t);
        const Vec3 v = spherical_direction(radians(t), radians(20.0));
        // Signed: the projected area [C19 Eq. 17]; front-facing only: the closed form of Eq. 13.
        CHECK(hemisphere_integral([&](const Vec3& m) { return p.D(m) * dot(v, m); }, 0.02, nullptr,
                                  1e-8) == doctest::Approx(p.projected_area(v)).epsilon(1e-5));
        CHECK(hemisphere_integral([&](const Vec3& m) { return p.D(m) * dot(v, m); }, 0.02, &v,
                                  1e-8) == doctest::Approx(p.visible_area(v)).epsilon(1e-5));
    }
    // Reciprocity of Eq. 7.
    const Vec3 i = spherical_direction(radians(35.0), radians(10.0));
    const Vec3 o = spherical_direction(radians(65.0), radians(200.0));
    double f1 = 0, f2 = 0;
    p.eval(i, o, &f1);
    p.eval(o, i, &f2);
    CHECK(f1 == doctest::Approx(f2).epsilon(1e-12));
}

TEST_CASE("a normal map written by gonio integrates back into its surface (Frankot-Chellappa)") {
    const HeightField s = brushed_surface(32);
    const std::string path =
        (std::filesystem::temp_directory_path() / "gonio_test_normals.exr").string();
    write_normal_exr(path, s, {});
    const HeightField back = read_height_exr(path);
    std::filesystem::remove(path);
    REQUIRE(back.n == s.n);
    double worst = 0;
    for (int y = 0; y < s.n; ++y)
        for (int x = 0; x < s.n; ++x)
            worst = std::max(
                {worst, std::abs(back.p(x, y) - s.p(x, y)), std::abs(back.q(x, y) - s.q(x, y))});
    CHECK(worst < 1e-4); // float normals and heights
}

TEST_CASE(
    "C19: the fitted mixture reproduces a smooth map's facet distribution (total variation)") {
    // C19 fits one lobe per texel to a map resolved by its texels. A map correlated over ~8 texels:
    // (a white-noise map, correlated over less than a texel, comes out with heavier tails: each
    // lobe's variance is a sample variance over a few texels -- TV 0.08 against 0.016 here).
    SurfaceSpec spec;
    spec.size = 64;
    spec.generator = &heitz_generator();
    spec.correlation_length = 8;
    const HeightField s = generate_surface(Beckmann(0.1, 0.4), spec, 2);
    const PBrdfModel p(fit_slope_lobes(s), FresnelTerm::mirror());
    const BeckersSensor sensor(145);
    // The facets: two triangles per texel, of equal projected area.
    const double facets = 2.0 * s.n * s.n;
    std::vector<double> measured(size_t(sensor.cell_count()), 0.0);
    for (int y = 0; y < s.n; ++y)
        for (int x = 0; x < s.n; ++x)
            for (int t = 0; t < 2; ++t) {
                double sp, sq;
                s.triangle_slopes(x, y, t, sp, sq);
                measured[size_t(sensor.lookup(HeightField::normal_of_slopes(sp, sq)))] +=
                    1 / facets;
            }
    const std::vector<double> model =
        integrate_over_cells(sensor, [&](const Vec3& m) { return p.D(m) * m.z; });
    double tv = 0, iid = 0;
    for (size_t c = 0; c < model.size(); ++c) {
        tv += 0.5 * std::abs(measured[c] - model[c]);
        // An ideal sample of as many facets drawn from D_P: E|X/N - p| ~ sqrt(2 p (1 - p) / (pi
        // N)).
        iid += 0.5 * std::sqrt(2 * model[c] * (1 - model[c]) / (kPi * facets));
    }
    CAPTURE(tv);
    CAPTURE(iid);
    CHECK(tv < 2 * iid);
}
