// A run as a library object (gonio/run/run.h): its executors give the same result bit for bit,
// units are numbered in one place and travel exactly, the ensemble's sizing is a piece of its
// own, every thread computes in one floating-point mode, and invariants are CHECKs.
#include "check_death.h"
#include "core/check.h"
#include "core/float_mode.h"
#include "core/output_files.h"
#include "core/parallel.h"
#include "gonio/config/config.h"
#include "gonio/run/ensemble_plan.h"
#include "gonio/run/run.h"
#include "gonio/run/unit_file.h"

#include <atomic>
#include <cstring>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <unistd.h>
#include <xmmintrin.h>

using namespace gonio;
using namespace gonio::test;
namespace fs = std::filesystem;

namespace {
const char* kTwoCases = R"(seed = 11
[beam]
theta_i = [0, 50, 80]
phi_i = [0, 30]
[sensor]
cells = 145
[surface]
size = 32
iterations = 10
[trace]
rays = 4096
batches = 4
[[case]]
name = "mirror"
ndf = { type = "beckmann", alpha = 0.5 }
model = { models = ["l1", "vcavity"], vcavity_rays = 2048 }
[[case]]
name = "gold_ensemble"
ndf = { type = "ggx", alpha = 0.3 }
material = { type = "conductor", ior = "Au" }
surface = { realisations = 2 }
)";

// Every array of a result that is data (timings left out), in a fixed order.
std::vector<const Array*> arrays_of(const CaseResult& c) {
    const SimulationResult& s = c.simulation;
    std::vector<const Array*> out;
    for (const Estimate* e :
         {&s.reflected.distribution, &s.reflected.order_energy, &s.reflected.first,
          &s.reflected.higher, &s.reflected.all, &s.reflected.first_albedo,
          &s.reflected.second_albedo, &s.reflected.higher_albedo, &s.reflected.all_albedo,
          &s.absorbed, &s.capped, &s.lost})
        out.push_back(&e->mean), out.push_back(&e->error);
    for (const Array* a : {&s.unaccounted, &s.rays, &s.segments, &s.rounds, &s.achieved_error,
                           &s.realisations, &s.share_l1_albedo, &s.share_linf_cells})
        out.push_back(a);
    for (const ComparisonArrays& k : s.comparisons)
        for (const Array* a : {&k.relative_difference.mean, &k.relative_difference.error,
                               &k.distance.mean, &k.sigmas, &k.ratio.mean, &k.ratio.error})
            out.push_back(a);
    for (const ModelResult& m : c.models)
        for (const Array* a : {&m.brdf, &m.energy, &m.albedo, &m.brdf_stderr, &m.albedo_stderr,
                               &m.l1, &m.l2plus_albedo})
            out.push_back(a);
    return out;
}

// The two results hold the same numbers, bit for bit.
void check_same(const RunResult& a, const RunResult& b, const std::string& what) {
    CAPTURE(what);
    REQUIRE(a.cases.size() == b.cases.size());
    for (size_t c = 0; c < a.cases.size(); ++c) {
        const auto x = arrays_of(a.cases[c]), y = arrays_of(b.cases[c]);
        REQUIRE(x.size() == y.size());
        for (size_t k = 0; k < x.size(); ++k) {
            CAPTURE(c);
            CAPTURE(k);
            CAPTURE(x[k]->long_name);
            REQUIRE(x[k]->data.size() == y[k]->data.size());
            if (!x[k]->data.empty()) // (memcmp's pointers may not be null, even for 0 bytes)
                CHECK(std::memcmp(x[k]->data.data(), y[k]->data.data(),
                                  x[k]->data.size() * sizeof(double)) == 0);
        }
        CHECK(a.cases[c].simulation.stop == b.cases[c].simulation.stop);
    }
}

fs::path fresh(const std::string& name) {
    const fs::path d =
        fs::temp_directory_path() / ("gonio_run_api_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}
} // namespace

TEST_CASE("a run is a library call, and its executors give its result bit for bit") {
    const Config cfg = parse_config(kTwoCases, "two.toml");
    const RunResult whole = run_local(cfg, {});
    REQUIRE(whole.cases[1].simulation.error_scope == ErrorScope::rays_and_surface);
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        RunOptions o;
        o.threads = 1;
        check_same(whole, run_local(cfg, o), "one thread");
    }
    const fs::path d = fresh("executors");
    std::vector<std::string> parts;
    long long units = 0;
    for (int i = 0; i < 3; ++i) {
        parts.push_back((d / ("p" + std::to_string(i) + ".h5")).string());
        units += run_shard(cfg, {}, Shard{i, 3}, parts.back());
    }
    CHECK(units == UnitLayout(cfg).total());
    check_same(whole, merge_parts({parts[2], parts[0], parts[1]}, {}), "three shards merged");
    // Stopped after 5 units, then resumed from the checkpoint.
    const std::string checkpoint = (d / "run.checkpoint").string();
    RunOptions stopping;
    int done = 0;
    stopping.observer.unit_done = [&](const UnitId&) { ++done; };
    stopping.stop_requested = [&] { return done >= 5; };
    CHECK_THROWS_AS(run_local(cfg, stopping, {checkpoint, false}), Interrupted);
    UnitFileHeader header;
    CHECK(read_unit_file(checkpoint, &header).size() >= 5);
    int resumed = -1;
    RunOptions resuming;
    resuming.observer.resumed = [&](long long n, long long) { resumed = int(n); };
    check_same(whole, run_local(cfg, resuming, {checkpoint, true}), "stopped and resumed");
    CHECK(resumed >= 5);
    fs::remove_all(d);
}

TEST_CASE("the models alone are the models of the run") {
    const Config cfg = parse_config(kTwoCases, "two.toml");
    const RunResult traced = run_local(cfg, {}), models = run_models(cfg, {});
    for (size_t c = 0; c < 2; ++c)
        for (size_t m = 0; m < traced.cases[c].models.size(); ++m) {
            const ModelResult &a = traced.cases[c].models[m], &b = models.cases[c].models[m];
            CHECK(a.brdf.data == b.brdf.data);
            CHECK(a.brdf_stderr.data == b.brdf_stderr.data);
        }
}

TEST_CASE("units are numbered in one place and travel exactly") {
    const Config cfg = parse_config(kTwoCases, "two.toml");
    const UnitLayout layout(cfg);
    CHECK(layout.total() == 12);
    for (long long u = 0; u < layout.total(); ++u) CHECK(layout.number(layout.unit(u)) == u);
    CHECK(layout.number({1, 2, 1}) == 11);
    CHECK(fails_check([&] { (void)layout.unit(12); }));
    // A unit with traces and models, through bytes and back.
    const fs::path d = fresh("units");
    const std::string part = (d / "p.h5").string();
    run_shard(cfg, {}, Shard{0, 12}, part); // unit 0 alone
    std::vector<NumberedUnit> got = read_unit_file(part, nullptr);
    REQUIRE(got.size() == 1);
    const std::vector<char> bytes = serialise(got[0].result);
    CHECK(serialise(deserialise(bytes)) == bytes);
    REQUIRE(got[0].result.models.size() == 2);
    CHECK(got[0].result.models[1].monte_carlo());
    // Cut short, or with a count the bytes cannot hold: refused, not read past the end.
    CHECK_THROWS(deserialise({bytes.begin(), bytes.begin() + long(bytes.size() / 2)}));
    std::vector<char> lying = bytes;
    for (int k = 0; k < 8; ++k) lying[size_t(k)] = char(0x7f); // the member count
    CHECK_THROWS(deserialise(lying));
    fs::remove_all(d);
}

TEST_CASE("an ensemble's target is met in two stages (Stein's procedure)") {
    AccuracyTarget t;
    t.relative_error = 0.01;
    t.max_rays = 1'000'000;
    t.max_seconds = 100;
    auto plan = [&](EnsembleStatus s, double share = 1.0) {
        return plan_ensemble(t, 64, s, [share] { return share; });
    };
    // Without a target: the configured surfaces, once.
    CHECK(plan_ensemble(AccuracyTarget{}, 64, {}, [] { return 1.0; }).stop == StopReason::rays);
    // The pilot sizes the ensemble: R' = R e^2 / g^2 x 1.05, at least twice R.
    EnsembleStep s = plan({1, 4, 4000, 1000, 0.02, 1.0});
    CHECK(!s.done);
    CHECK(s.wanted == 17);        // ceil(4 x 4 x 1.05)
    CHECK(s.per_surface == 1000); // the surfaces carry the variance: no more rays each
    CHECK(plan({1, 4, 4000, 1000, 0.011, 1.0}).wanted == 8); // at least twice the pilot
    // Where the rays carry the variance, the new surfaces get more rays each.
    CHECK(plan({1, 4, 4000, 1000, 0.02, 1.0}, 0.0).per_surface > 1000);
    // The sized pass reports what it achieved, met or not.
    CHECK(plan({2, 17, 17000, 1000, 0.009}).stop == StopReason::target);
    CHECK(plan({2, 17, 17000, 1000, 0.012}).stop == StopReason::target_not_met);
    // Budgets: time, surfaces, rays.
    CHECK(plan({1, 4, 4000, 1000, 0.02, 200}).stop == StopReason::max_seconds);
    CHECK(plan_ensemble(t, 4, {1, 4, 4000, 1000, 0.02, 1}, [] { return 1.0; }).stop ==
          StopReason::max_realisations);
    CHECK(plan({1, 4, 999'500, 1000, 0.02, 1}).stop == StopReason::max_rays);
}

TEST_CASE("every task of the library's parallel loops computes in the one floating-point mode") {
    // Workers left in another mode (as Embree leaves them, or a caller's own code) ...
    tbb::parallel_for(0, 100000, [](int) { _mm_setcsr(0x1f80); });
    std::atomic<int> outside{0};
    gonio::parallel_for(0, 100000, [&](int) {
        if (!in_result_float_mode()) ++outside;
    });
    CHECK(outside == 0); // ... compute in it all the same
    use_result_float_mode();
    CHECK(in_result_float_mode());
}

TEST_CASE("an invariant that fails is a CHECK: it aborts, naming the condition") {
    CHECK(fails_check([] { GONIO_CHECK(1 + 1 == 3); }));
    CHECK(!fails_check([] { GONIO_CHECK(1 + 1 == 2); }));
}

TEST_CASE("outputs appear together or not at all, and a killed writer's temporaries are cleaned") {
    const fs::path d = fresh("outputs");
    const std::string a = (d / "a.png").string(), b = (d / "b.exr").string();
    {
        OutputSet files(false);
        std::ofstream(files.add(a)) << "a";
        std::ofstream(files.add(b)) << "b";
        fs::create_directory(b); // the second cannot take its place
        CHECK_THROWS_WITH_AS(files.commit(), doctest::Contains("b.exr"), std::runtime_error);
    }
    CHECK(!fs::exists(a)); // the first was renamed, then taken back
    fs::remove(b);
    for (const auto& e : fs::directory_iterator(d))
        CHECK(e.path().string().find(".tmp-") == std::string::npos);
    {
        OutputSet files(false);
        std::ofstream(files.add(a)) << "a";
        // destroyed uncommitted: its temporary goes
    }
    CHECK(fs::is_empty(d));
    {
        OutputSet files(false);
        std::ofstream(files.add(a)) << "a";
        std::ofstream(files.add(b)) << "b";
        files.commit();
    }
    CHECK(fs::exists(a));
    CHECK(fs::exists(b));
    // A temporary of a process that no longer runs is removed by the next writer; one of a
    // living process (this one) is not.
    const std::string dead = a + ".tmp-999999999", alive = a + ".tmp-" + std::to_string(::getpid());
    std::ofstream(dead) << "x";
    std::ofstream(alive) << "x";
    CHECK(remove_stale_temporaries(a) == 1);
    CHECK(!fs::exists(dead));
    CHECK(fs::exists(alive));
    fs::remove_all(d);
}
