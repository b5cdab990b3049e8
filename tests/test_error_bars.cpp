// The standard errors gonio reports (batch means, jackknife) against the spread of independent
// seeds on one surface, and the target-accuracy mode. A reported error sigma and the spread s of
// N seeds agree when (N - 1) s^2 / sigma^2 is a plausible chi-square variable with N - 1 degrees
// of freedom (sigma^2 is the mean over the seeds of the squared reported errors, itself good to a
// few per cent with N (B - 1) degrees of freedom); two-sided, Sidak-corrected 1 % levels.
#include "core/batch_means.h"
#include "core/chi_square.h"
#include "gonio/material/material.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/microfacet_model.h"
#include "gonio/model/model_comparison.h"
#include "gonio/model/vcavity_estimator.h"
#include "gonio/trace/gonioreflectometer.h"
#include "heightfield/generate.h"
#include "heightfield/ndf/beckmann.h"

#include <cmath>
#include <doctest/doctest.h>
#include <tbb/global_control.h>

using namespace gonio;

namespace {

// Accumulates one quantity over seeds: its values and its reported errors.
struct Spread {
    std::vector<double> value, reported;
    void add(double v, double err) { value.push_back(v), reported.push_back(err); }
    // (N - 1) s^2 / mean(sigma^2) and its two-sided chi-square p-value.
    double p_value() const {
        const size_t n = value.size();
        double mean = 0, ms = 0, ss = 0;
        for (size_t k = 0; k < n; ++k)
            mean += value[k] / double(n), ms += reported[k] * reported[k] / double(n);
        for (double v : value) ss += (v - mean) * (v - mean);
        const double p = chi_square_p_value(ss / ms, int(n) - 1);
        return 2 * std::min(p, 1 - p);
    }
    double ratio() const { // s / rms(sigma), for the messages
        const size_t n = value.size();
        double mean = 0, ms = 0, ss = 0;
        for (size_t k = 0; k < n; ++k)
            mean += value[k] / double(n), ms += reported[k] * reported[k] / double(n);
        for (double v : value) ss += (v - mean) * (v - mean);
        return std::sqrt(ss / double(n - 1) / ms);
    }
};

HeightField test_surface() {
    SurfaceSpec s;
    s.size = 64;
    s.iterations = 50;
    return generate_surface(Beckmann(0.5), s, 2);
}

} // namespace

TEST_CASE("batch means: the standard error of the mean, and the jackknife of a linear statistic") {
    const std::vector<double> x{1, 2, 3, 4, 6}; // five batches of one quantity
    // sum (x - 3.2)^2 = 14.8; sqrt(14.8 / (5 * 4)).
    CHECK(batch_stderr(x, 5)[0] == doctest::Approx(std::sqrt(14.8 / 20)).epsilon(1e-14));
    CHECK(batch_mean(x, 5)[0] == doctest::Approx(3.2).epsilon(1e-14));
    // The jackknife of the mean is the batch-means error exactly.
    const double j = jackknife_stderr(5, [&](int b) { return mean_without(3.2, x[size_t(b)], 5); });
    CHECK(j == doctest::Approx(std::sqrt(14.8 / 20)).epsilon(1e-12));
    CHECK(batch_stderr(1, [](int) { return 1.0; }) == 0.0); // one batch: nothing to say
}

TEST_CASE("reported errors agree with the spread of 40 seeds on one surface") {
    const HeightField surface = test_surface();
    const Scene scene(surface);
    const BeckersSensor sensor(100);
    const SpecularReflector gold(FresnelTerm::conductor({{0.21, 3.272}}));
    const Beckmann ndf(0.5);
    const MicrofacetModel model(ndf, FresnelTerm::conductor({{0.21, 3.272}}),
                                MaskingForm::height_correlated);
    const Vec3 wi = spherical_direction(radians(50.0), 0.3);
    ModelIncidence m;
    m.energy = model_cell_energy(model, wi, sensor, CellQuadrature{});
    m.relative_tolerance = 1e-6;
    const int seeds = 40;
    Spread l1, l2plus, absorbed, distance, cells;
    double peak = 0;
    for (double e : m.energy) peak = std::max(peak, e);
    for (int seed = 1; seed <= seeds; ++seed) {
        TraceSettings st;
        st.rays = 8192, st.seed = std::uint64_t(seed);
        const TraceResult r = trace_incidence(scene, gold, sensor, wi, st);
        REQUIRE(r.batches == 32);
        l1.add(r.ledger.reflected[0], r.ledger_stderr.reflected[0]);
        const std::vector<double> l2 =
            sum_orders(r.ledger_batches.reflected, r.batches, r.orders, 1, r.orders);
        l2plus.add(batch_mean(l2, r.batches)[0], batch_stderr(l2, r.batches)[0]);
        absorbed.add(r.ledger.absorbed[0], r.ledger_stderr.absorbed[0]);
        const Comparison c = compare_model(r, ModelTarget::l1, m);
        distance.add(c.distance[0], c.distance_stderr[0]);
        // The brightest cells of Model L1, pooled: one value per seed and cell.
        for (int cell = 0; cell < sensor.cell_count(); ++cell)
            if (m.energy[size_t(cell)] > 0.3 * peak)
                cells.add(r.energy[size_t(cell)], r.energy_stderr[size_t(cell)]);
    }
    const double level = sidak_level(0.01, 4);
    for (const auto& [name, s] : {std::pair<const char*, const Spread*>{"L1 albedo", &l1},
                                  {"L2+ albedo", &l2plus},
                                  {"absorbed", &absorbed},
                                  {"distance to Model L1", &distance}}) {
        CAPTURE(name);
        CAPTURE(s->ratio());
        CHECK(s->p_value() > level);
    }
    // Cells: pooled over the bright cells, (N - 1) sum_c s_c^2 / sigma_c^2 is chi-square with
    // cells (N - 1) degrees of freedom.
    const size_t per_seed = cells.value.size() / seeds;
    REQUIRE(per_seed >= 3);
    double stat = 0;
    for (size_t c = 0; c < per_seed; ++c) {
        double mean = 0, ms = 0, ss = 0;
        for (int s = 0; s < seeds; ++s) {
            mean += cells.value[size_t(s) * per_seed + c] / seeds;
            ms += std::pow(cells.reported[size_t(s) * per_seed + c], 2) / seeds;
        }
        for (int s = 0; s < seeds; ++s)
            ss += std::pow(cells.value[size_t(s) * per_seed + c] - mean, 2);
        stat += ss / ms;
    }
    const double p = chi_square_p_value(stat, int(per_seed) * (seeds - 1));
    CAPTURE(per_seed);
    CAPTURE(stat / double(per_seed * (seeds - 1)));
    CHECK(2 * std::min(p, 1 - p) > 0.01);
}

TEST_CASE("the V-cavity estimator's errors agree with the spread of 40 seeds") {
    const BeckersSensor sensor(64);
    const Beckmann ndf(0.8);
    const SpecularReflector gold(FresnelTerm::conductor({{0.21, 3.272}}));
    const Vec3 wi = spherical_direction(radians(70.0), 0.0);
    Spread l1, higher;
    for (int seed = 1; seed <= 40; ++seed) {
        TraceSettings st;
        st.rays = 4096, st.orders = 2, st.seed = std::uint64_t(seed);
        const TraceResult v = vcavity_estimate(ndf, gold, sensor, wi, st);
        l1.add(v.ledger.reflected[0], v.ledger_stderr.reflected[0]);
        higher.add(v.ledger.reflected[1], v.ledger_stderr.reflected[1]);
    }
    CAPTURE(l1.ratio());
    CAPTURE(higher.ratio());
    CHECK(l1.p_value() > sidak_level(0.01, 2));
    CHECK(higher.p_value() > sidak_level(0.01, 2));
}

TEST_CASE("an accuracy target: met, said, reproducible, and its error is the spread of 12 seeds") {
    const HeightField surface = test_surface();
    const Scene scene(surface);
    const BeckersSensor sensor(100);
    const SpecularReflector mirror(FresnelTerm::mirror());
    const Vec3 wi = spherical_direction(radians(60.0), 0.0);
    TraceSettings st;
    st.rays = 2048;
    st.target.relative_error = 2e-3; // on the L1 albedo
    Spread l1;
    for (int seed = 1; seed <= 12; ++seed) {
        st.seed = std::uint64_t(seed);
        const TraceResult r = trace_incidence(scene, mirror, sensor, wi, st);
        CHECK(r.stop == StopReason::target);
        CHECK(r.achieved_error <= 2e-3);
        CHECK(r.rounds > 1); // 2048 rays alone are far from it
        CHECK(r.ledger_stderr.reflected[0] / r.ledger.reflected[0] ==
              doctest::Approx(r.achieved_error));
        l1.add(r.ledger.reflected[0], r.ledger_stderr.reflected[0]);
    }
    CAPTURE(l1.ratio());
    CHECK(l1.p_value() > 0.01);
    SUBCASE("the same for a seed whatever the thread count") {
        st.seed = 3;
        TraceResult one;
        {
            tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
            one = trace_incidence(scene, mirror, sensor, wi, st);
        }
        const TraceResult two = trace_incidence(scene, mirror, sensor, wi, st);
        CHECK(one.rays == two.rays);
        CHECK(one.energy == two.energy);
        CHECK(one.energy_stderr == two.energy_stderr);
    }
    SUBCASE("a ray budget stops it first, and says so") {
        st.seed = 1;
        st.target.max_rays = 20000;
        const TraceResult r = trace_incidence(scene, mirror, sensor, wi, st);
        CHECK(r.stop == StopReason::max_rays);
        CHECK(r.rays <= 20000);
        CHECK(r.achieved_error > 2e-3);
    }
    SUBCASE("a cell target counts the cells above its fraction of the peak") {
        st.seed = 1;
        st.target.quantity = TargetQuantity::l1_cells;
        st.target.relative_error = 0.05;
        const TraceResult r = trace_incidence(scene, mirror, sensor, wi, st);
        CHECK(r.stop == StopReason::target);
        double peak = 0, worst = 0;
        for (int c = 0; c < 100; ++c)
            peak = std::max(peak, r.energy[size_t(c)] / sensor.cell(c).projected_solid_angle);
        for (int c = 0; c < 100; ++c)
            if (r.energy[size_t(c)] / sensor.cell(c).projected_solid_angle >= 0.1 * peak)
                worst = std::max(worst, r.energy_stderr[size_t(c)] / r.energy[size_t(c)]);
        CHECK(worst == doctest::Approx(r.achieved_error));
        CHECK(worst <= 0.05);
    }
}
