// A run as a library call (gonio/run/run.h), its phase timings, and the command that lists the
// declared keys.
#include "cli_harness.h"
#include "gonio/config/config.h"
#include "gonio/io/hdf5_handles.h"
#include "gonio/run/run.h"

#include <algorithm>
#include <doctest/doctest.h>

using namespace gonio;
using namespace gonio::test;

namespace {
const char* kSmall = R"(seed = 3
[ndf]
type = "beckmann"
alpha = 0.5
[beam]
theta_i = [0, 60]
[sensor]
cells = 145
[surface]
size = 64
iterations = 20
[trace]
rays = 16384
batches = 4
)";
} // namespace

TEST_CASE("run_local: one call builds the case, traces its sweep and returns typed results") {
    const Config cfg = parse_config(kSmall, "small.toml");
    int started = 0, finished = 0;
    RunOptions options;
    options.observer.started = [&](const std::string&) { ++started; };
    options.observer.incidence = [&](const IncidenceReport& r) {
        ++finished;
        CHECK(r.trace != nullptr);
        CHECK(r.simulation->incidences() == size_t(finished));
    };
    const RunResult run = run_local(cfg, options);
    REQUIRE(run.cases.size() == 1);
    const CaseResult& r = run.cases[0];
    CHECK(started == 2);
    CHECK(finished == 2);
    CHECK(r.simulation.complete());
    REQUIRE(r.models.size() == 1);
    CHECK(r.models[0].name == "l1");
    // L1 + L2+ is every order, and a mirror loses nothing.
    for (size_t t = 0; t < 2; ++t) {
        const double l1 = r.simulation.reflected.first_albedo.mean.at({t, 0, 0});
        const double l2 = r.simulation.reflected.higher_albedo.mean.at({t, 0, 0});
        CHECK(l1 + l2 == doctest::Approx(r.simulation.reflected.all_albedo.mean.at({t, 0, 0})));
        CHECK(r.simulation.reflected.all_albedo.mean.at({t, 0, 0}) == doctest::Approx(1.0));
    }
    std::vector<std::string> names;
    for (const auto& [name, s] : r.phases.phases()) {
        names.push_back(name);
        CHECK(s >= 0);
    }
    CHECK(names == std::vector<std::string>{"ndf", "surface", "scene", "models_setup", "trace",
                                            "model_l1", "compare"});
    // The models alone: no surface for Model L1, the same model albedos as with the trace.
    const RunResult m = run_models(cfg, {});
    CHECK(m.cases[0].simulation.incidences() == 0);
    CHECK(m.cases[0].models[0].albedo.data == r.models[0].albedo.data);
}

TEST_CASE("gonio run stores every phase's time, and the phases add up to the wall time") {
    const fs::path d = fresh_dir("phases");
    write(d / "small.toml", kSmall);
    const Run r = run_gonio(d, "run small.toml -o out.h5 --quiet --no-cache");
    REQUIRE(r.code == 0);
    h5::silence_errors();
    h5::Handle f(H5Fopen((d / "out.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                 "open out.h5");
    double sum = 0, wall = 0;
    for (const std::string& phase : h5::read_string_list_attribute(f, "phases")) {
        const double s = h5::read_double_attribute(f, "phase_" + phase + "_seconds");
        CHECK(s >= 0);
        (phase == "wall" ? wall : sum) += s;
    }
    CHECK(wall > 0);
    CHECK(sum <= wall * 1.0001);
    // What no phase holds is a fixed cost (creating the thread pool, opening the output): 10 % of
    // this small run's wall time or 20 ms, whichever is more (a loaded machine stretches it).
    CHECK(wall - sum <= std::max(0.1 * wall, 0.02));
    fs::remove_all(d);
}

TEST_CASE("gonio keys lists every declared key with its range and default") {
    const fs::path d = fresh_dir("keys");
    const Run r = run_gonio(d, "keys");
    REQUIRE(r.code == 0);
    for (const KeyGroup& g : config_key_groups())
        for (const Key& k : g.keys) {
            const std::string path = g.section.empty() ? k.name : g.section + "." + k.name;
            CAPTURE(path);
            CHECK(r.out.find("  " + path + "\n      " + k.type_text() + "; default " +
                             k.default_text()) != std::string::npos);
        }
    CHECK(r.out.find("ndf.alpha") != std::string::npos);
    CHECK(r.out.find("number in [1e-06, 100]") != std::string::npos);
    fs::remove_all(d);
}

TEST_CASE("gonio surface and gonio ndf need no beam, gonio run and gonio model do") {
    const fs::path d = fresh_dir("nobeam");
    write(d / "s.toml",
          "[ndf]\ntype = \"ggx\"\nalpha = 0.3\n[surface]\nsize = 32\niterations = 5\n");
    CHECK(run_gonio(d, "ndf s.toml").code == 0);
    CHECK(run_gonio(d, "surface s.toml -o s.exr --no-cache --quiet").code == 0);
    const Run run = run_gonio(d, "run s.toml -o s.h5 --no-cache");
    CHECK(run.code == 2);
    CHECK(run.err.find("key 'beam.theta_i': missing (gonio run needs an incidence sweep)") !=
          std::string::npos);
    CHECK(!fs::exists(d / "s.h5"));
    CHECK(run_gonio(d, "model s.toml -o s.h5").code == 2);
    fs::remove_all(d);
}
