// gonio masking: the weak white furnace on generated surfaces, the projected-area G1 against
// Smith's from the surface's own facet NDF (the same quantity, Heitz 2014), the measurement's
// independence from the threads, and the height-direction-correlated Smith form.
#include "gonio/masking/facet_sampler.h"
#include "gonio/masking/masking_estimates.h"
#include "gonio/trace/scene.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/ndf/ndf_table.h"
#include "heightfield/ndf/tabulated_ndf.h"
#include "heightfield/surface_source.h"

#include <cmath>
#include <doctest/doctest.h>
#include <tbb/global_control.h>

using namespace gonio;

namespace {

HeightField surface_of(const Ndf& ndf, int size, std::uint64_t seed) {
    SurfaceSpec spec;
    spec.size = size;
    spec.iterations = 60;
    spec.seed = seed;
    SurfaceOrigin origin;
    return obtain_surface(ndf, spec, SurfaceCache(""), 2, origin);
}

MaskingGrid g1_grid() {
    MaskingGrid g;
    g.theta_o_deg = {0, 10, 20, 30, 40, 50, 60, 70, 80, 85, 89};
    g.phi_o_deg = {0, 90};
    g.normal_bins = 33;
    g.height_bins = 4;
    return g;
}

} // namespace

TEST_CASE("weak white furnace: integral of G1 <w, m>+ D_s = cos theta at every w (Beckmann, GGX "
          "alpha 0.1-1.5)") {
    // Exact on any height field [Heitz 2014 section 3]: the measurement's self-test. 2^15 points
    // per surface, 11 x 2 directions, 8 surfaces: every |z| within 3 (the bar) and the
    // largest within the Sidak-corrected 1 % level of the 176 tests (3.86).
    const MaskingGrid grid = g1_grid();
    double worst = 0;
    for (double alpha : {0.1, 0.5, 1.0, 1.5})
        for (int family = 0; family < 2; ++family) {
            std::unique_ptr<Ndf> ndf;
            if (family == 0)
                ndf = std::make_unique<Beckmann>(alpha);
            else
                ndf = std::make_unique<Ggx>(alpha);
            CAPTURE(ndf->describe());
            const HeightField s = surface_of(*ndf, 128, 7);
            const Scene scene(s);
            const MaskingCounts c = measure_masking(s, scene, grid, 1 << 15, 0, 11);
            const TabulatedNdf facets(
                facet_ndf_table(s, kFacetTable.theta_intervals, kFacetTable.phi_count), "surface",
                "height_map");
            const MaskingEstimates e = estimate_masking({c}, grid, *ndf, facets);
            const Array &z = e["furnace_z"], &gp = e["g1_projected"],
                        &gpe = e["g1_projected_stderr"], &smith = e["g1_smith_surface"];
            for (size_t k = 0; k < z.data.size(); ++k) {
                CAPTURE(k);
                CHECK(std::abs(z.data[k]) <= 3.0);
                worst = std::max(worst, std::abs(z.data[k]));
                // The projected-area G1 is Smith's 1 / (1 + Lambda) of D_s: the same quantity, up
                // to the facet table's binning of D_s (kFacetTable) and the points' noise.
                if (gpe.data[k] > 0)
                    CHECK(std::abs(gp.data[k] - smith.data[k]) <=
                          4 * gpe.data[k] + 0.01 * (1 - smith.data[k]) + 1e-4);
            }
        }
    MESSAGE("largest |z| of the weak furnace: " << worst);
    CHECK(worst <= 3.86);
}

TEST_CASE("gonio masking's counts do not depend on the threads") {
    const Ggx ndf(0.5);
    const HeightField s = surface_of(ndf, 64, 3);
    const Scene scene(s);
    MaskingGrid grid = g1_grid();
    grid.theta_i_deg = {45};
    grid.phi_i_deg = {0};
    grid.g2_theta_o_deg = {0, 45, 80};
    grid.g2_dphi_deg = {0, 90, 180};
    MaskingCounts one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = measure_masking(s, scene, grid, 20000, 5000, 3);
    }
    const MaskingCounts two = measure_masking(s, scene, grid, 20000, 5000, 3);
    CHECK(one.g1_visible == two.g1_visible);
    CHECK(one.g2_visible == two.g2_visible);
    CHECK(one.furnace_sum == two.furnace_sum);
    CHECK(one.projected_sum == two.projected_sum);
}

TEST_CASE("height-direction-correlated Smith G2 [Heitz 2014 Eq. 101]: its limits") {
    const double li = 0.3, lo = 0.7;
    const Vec3 i = spherical_direction(radians(60), 0), same = spherical_direction(radians(70), 0),
               opposite = spherical_direction(radians(70), kPi);
    // Same azimuth: lambda(0) = 0, masking and shadowing fully correlated: G1 of the larger Lambda.
    CHECK(smith_g2(li, lo, i, same, MaskingForm::height_direction_correlated) ==
          doctest::Approx(1.0 / (1.0 + lo)));
    // Opposite: lambda(pi) = 4.41 pi / (4.41 pi + 1), between height-correlated and that.
    const double l = 4.41 * kPi / (4.41 * kPi + 1.0);
    CHECK(smith_g2(li, lo, i, opposite, MaskingForm::height_direction_correlated) ==
          doctest::Approx(1.0 / (1.0 + lo + l * li)));
    for (const Vec3& o : {same, opposite}) {
        const double hd = smith_g2(li, lo, i, o, MaskingForm::height_direction_correlated);
        CHECK(hd >= smith_g2(li, lo, i, o, MaskingForm::height_correlated));
        CHECK(hd >= smith_g2(li, lo, i, o, MaskingForm::uncorrelated));
        CHECK(hd <= 1.0 / (1.0 + std::max(li, lo)));
    }
    // A direction along the normal has no azimuth and Lambda 0: every form gives G1 of the other.
    CHECK(smith_g2(0.0, lo, Vec3{0, 0, 1}, opposite, MaskingForm::height_direction_correlated) ==
          doctest::Approx(1.0 / (1.0 + lo)));
}
