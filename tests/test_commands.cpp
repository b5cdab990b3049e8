// End-to-end: the gonio binary, its exit codes and messages, and the HDF5 result file.
#include "gonio/io/hdf5_handles.h"
#include "gonio/io/result_reader.h"
#include "tests/cli_harness.h"

#include <algorithm>
#include <cstdlib>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace gonio;
using namespace gonio::test;

namespace {
const char* kSmall = R"(seed = 3
[ndf]
type = "beckmann"
alpha = 0.5
[beam]
theta_i = [0, 60]
phi_i = [0, 90]
[sensor]
cells = 145
[[case]]
name = "mirror"
[[case]]
name = "gold"
material = { type = "conductor", ior = "Au" }
)";
} // namespace

TEST_CASE("gonio model writes a complete result file that gonio info reads") {
    const fs::path d = fresh_dir("model");
    write(d / "small.toml", kSmall);
    const Run r = run_gonio(d, "model small.toml -o out.h5 --quiet");
    CHECK(r.code == 0);
    CHECK(r.err.empty());
    REQUIRE(fs::exists(d / "out.h5"));
    CHECK(files_in(d) == 2); // the config and the result: no temporary file left behind

    const ResultSummary s = read_result_summary((d / "out.h5").string());
    CHECK(s.seed == 3);
    CHECK(s.attributes.at("config_toml") == kSmall);
    CHECK(s.attributes.at("command_line").find("model small.toml") != std::string::npos);
    CHECK(!s.attributes.at("git_hash").empty());
    REQUIRE(s.cases.size() == 2);
    CHECK(s.cases[0].name == "mirror");
    CHECK(s.cases[1].channels == 3);
    CHECK(s.cases[1].wavelength_nm == std::vector<double>{650, 550, 450});
    const std::vector<double>& albedo = s.cases[0].albedos.at("model_l1_albedo");
    REQUIRE(albedo.size() == 4); // 2 theta_i x 2 phi_i x 1 channel
    CHECK(std::abs(albedo[0] - 0.9430) <
          1e-3); // Beckmann 0.5, normal incidence (0.9430 by an independent quadrature)
    CHECK(albedo[0] ==
          doctest::Approx(albedo[1]).epsilon(1e-12)); // isotropic: phi_i does not matter

    const Run info = run_gonio(d, "info out.h5 --json");
    CHECK(info.code == 0);
    const nlohmann::json j = nlohmann::json::parse(info.out);
    CHECK(j.at("file_format") == "gonio-result 2");
    CHECK(j.at("seed") == 3);
    REQUIRE(j.at("cases").size() == 2);
    const nlohmann::json& mirror = j.at("cases")[0];
    CHECK(mirror.at("name") == "mirror");
    CHECK(mirror.at("models") == nlohmann::json::array({"l1"}));
    CHECK(j.at("cases")[1].at("wavelength_nm") == nlohmann::json::array({650, 550, 450}));
    REQUIRE(mirror.at("incidences").size() == 4);
    const nlohmann::json& last = mirror.at("incidences")[3];
    CHECK(last.at("theta_i") == 60);
    CHECK(last.at("phi_i") == 90);
    // Shortest round-trip: the number read back is the double in the file.
    CHECK(mirror.at("incidences")[0].at("model_l1_albedo")[0].get<double>() == albedo[0]);
    CHECK(mirror.at("timings").contains("model_l1"));
    CHECK(j.at("timings").at("wall").get<double>() >= 0);
    const Run text = run_gonio(d, "info out.h5");
    CHECK(text.code == 0);
    CHECK(text.out.find("case gold") != std::string::npos);
    fs::remove_all(d);
}

TEST_CASE("result file: cell coordinates are attached dimension scales with units") {
    const fs::path d = fresh_dir("scales");
    write(d / "small.toml", kSmall);
    REQUIRE(run_gonio(d, "model small.toml -o out.h5 -q").code == 0);
    h5::silence_errors();
    h5::Handle file(H5Fopen((d / "out.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                    "open");
    h5::Handle group(H5Gopen2(file, "gold", H5P_DEFAULT), H5Gclose, "group");
    h5::Handle brdf(H5Dopen2(group, "model_l1", H5P_DEFAULT), H5Dclose, "model_l1");
    // One scale per axis; the cell geometry and the wavelengths are coordinates named in the
    // `coordinates` attribute, each a variable along the cell (channel) scale.
    for (unsigned k = 0; k < 4; ++k) CHECK(H5DSget_num_scales(brdf, k) == 1);
    h5::Handle cell(H5Dopen2(group, "cell", H5P_DEFAULT), H5Dclose, "cell");
    h5::Handle channel(H5Dopen2(group, "channel", H5P_DEFAULT), H5Dclose, "channel");
    CHECK(H5DSis_attached(brdf, cell, 2) > 0);
    CHECK(H5DSis_attached(brdf, channel, 3) > 0);
    const std::string coordinates = h5::read_string_attribute(brdf, "coordinates");
    for (const char* name : {"theta_center", "phi_center", "theta_min", "theta_max", "phi_min",
                             "phi_max", "solid_angle", "projected_solid_angle", "wavelength"}) {
        CAPTURE(name);
        CHECK(coordinates.find(name) != std::string::npos);
        h5::Handle coord(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose, name);
        CHECK(H5DSis_scale(coord) <= 0);
        CHECK(H5DSis_attached(coord, std::string(name) == "wavelength" ? channel : cell, 0) > 0);
        const std::string units = h5::read_string_attribute(coord, "units");
        CHECK((units == "degree" || units == "sr" || units == "nm"));
    }
    const std::vector<std::string> models = h5::read_string_list_attribute(group, "models");
    CHECK(models == std::vector<std::string>{"l1"});
    CHECK(h5::attribute_is_array(group, "models"));
    CHECK(h5::read_string_list_attribute(file, "cases") ==
          std::vector<std::string>{"mirror", "gold"});
    CHECK(h5::read_string_attribute(brdf, "units") == "1/sr");
    // The BRDF is the cell energy over the projected solid angle.
    std::vector<hsize_t> dims;
    const std::vector<double> f = h5::read_doubles(group, "model_l1", &dims);
    const std::vector<double> e = h5::read_doubles(group, "model_l1_energy");
    const std::vector<double> proj = h5::read_doubles(group, "projected_solid_angle");
    REQUIRE(dims == std::vector<hsize_t>{2, 2, 145, 3});
    for (size_t k = 0; k < f.size(); k += 97)
        CHECK(f[k] == doctest::Approx(e[k] / proj[(k / 3) % 145]).epsilon(1e-14));
    fs::remove_all(d);
}

TEST_CASE("a bad config: one line naming file, line and key, exit code 2, no output file") {
    const fs::path d = fresh_dir("bad");
    write(d / "bad.toml", "[ndf]\ntype = \"beckmann\"\nalhpa = 0.5\n[beam]\ntheta_i = 0\n");
    const Run r = run_gonio(d, "model bad.toml -o out.h5");
    CHECK(r.code == 2);
    CHECK(r.err ==
          "gonio: error: bad.toml:3: key 'ndf.alhpa': unknown key (did you mean 'alpha'?); "
          "allowed here: type, alpha, alpha_x, alpha_y\n");
    CHECK(files_in(d) == 1); // only bad.toml

    write(d / "range.toml", "[ndf]\ntype = \"ggx\"\nalpha = -1\n[beam]\ntheta_i = 0\n");
    const Run range = run_gonio(d, "model range.toml -o out.h5");
    CHECK(range.code == 2);
    CHECK(range.err.find(
              "range.toml:3: key 'ndf.alpha': value -1 is out of range; allowed [1e-06, 100]") !=
          std::string::npos);
    const Run missing = run_gonio(d, "model nothere.toml -o out.h5");
    CHECK(missing.code == 2);
    CHECK(missing.err.find("nothere.toml: cannot open the config file") != std::string::npos);
    const Run set =
        run_gonio(d, "model range.toml --set ndf.alpha=0.3 --set beam.theta_i=95 -o out.h5");
    CHECK(set.code == 2);
    CHECK(set.err.find("key 'beam.theta_i': value 95 is out of range; allowed [0, 89.99]") !=
          std::string::npos);
    CHECK(files_in(d) == 2); // bad.toml, range.toml
    fs::remove_all(d);
}

TEST_CASE("an existing result is not replaced without --overwrite") {
    const fs::path d = fresh_dir("overwrite");
    write(d / "small.toml", kSmall);
    write(d / "out.h5", "precious");
    const Run r = run_gonio(d, "model small.toml -o out.h5 -q");
    CHECK(r.code != 0);
    CHECK(r.err.find("out.h5: exists; pass --overwrite") != std::string::npos);
    CHECK(slurp(d / "out.h5") == "precious");
    CHECK(files_in(d) == 2);
    CHECK(run_gonio(d, "model small.toml -o out.h5 -q --overwrite").code == 0);
    CHECK(read_result_summary((d / "out.h5").string()).cases.size() == 2);
    const Run info = run_gonio(d, "info small.toml");
    CHECK(info.code == 1);
    CHECK(info.err.find("small.toml: not an HDF5 file") != std::string::npos);
    fs::remove_all(d);
}

TEST_CASE("results do not depend on the thread count") {
    const fs::path d = fresh_dir("threads");
    write(d / "small.toml", kSmall);
    REQUIRE(run_gonio(d, "model small.toml -o one.h5 -q --threads 1").code == 0);
    REQUIRE(run_gonio(d, "model small.toml -o two.h5 -q --threads 2").code == 0);
    h5::silence_errors();
    for (const char* c : {"mirror", "gold"}) {
        std::vector<double> a, b;
        {
            h5::Handle f(H5Fopen((d / "one.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                         H5Fclose, "open");
            h5::Handle g(H5Gopen2(f, c, H5P_DEFAULT), H5Gclose, "group");
            a = h5::read_doubles(g, "model_l1");
        }
        {
            h5::Handle f(H5Fopen((d / "two.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                         H5Fclose, "open");
            h5::Handle g(H5Gopen2(f, c, H5P_DEFAULT), H5Gclose, "group");
            b = h5::read_doubles(g, "model_l1");
        }
        CHECK(a == b);
    }
    fs::remove_all(d);
}

TEST_CASE("every config error path: exit code 2, one line naming file and key, no file written") {
    const fs::path d = fresh_dir("errors");
    const std::string ok = "[ndf]\ntype = \"ggx\"\nalpha = 0.3\n[beam]\ntheta_i = 0\n";
    struct Bad {
        std::string text, extra_args, expect;
    };
    const Bad cases[] = {
        {"[ndf]\ntype = \"ggx\"\nalpa = 0.3\n[beam]\ntheta_i = 0\n", "",
         "c.toml:3: key 'ndf.alpa': unknown key"},
        {"[ndf]\ntype = \"ggx\"\nalpha = \"x\"\n[beam]\ntheta_i = 0\n", "",
         "c.toml:3: key 'ndf.alpha': must be a number"},
        {"[ndf]\ntype = \"ggx\"\nalpha = 0\n[beam]\ntheta_i = 0\n", "",
         "c.toml:3: key 'ndf.alpha': value 0 is out of range; allowed [1e-06, 100]"},
        {ok, "--set beam.theta_i=-1",
         "key 'beam.theta_i': value -1 is out of range; allowed [0, 89.99]"},
        {ok, "--set beam.phi_i=400",
         "key 'beam.phi_i': value 400 is out of range; allowed [0, 360]"},
        {ok, "--set sensor.cells=0",
         "key 'sensor.cells': value 0 is out of range; allowed [1, 1e+07]"},
        {ok, "--set model.masking=smith", "key 'model.masking': \"smith\" is not allowed"},
        {ok, "--set material.type=conductor --set material.ior=Xx", "key 'material.ior': "},
        {ok, "--set material.f0=0.5", "key 'material.f0': is not used by any case"},
        {"[ndf]\ntype = \"ggx\"\n", "", "c.toml:1: key 'ndf.alpha': missing"},
        {"[ndf\n", "", "c.toml:1: TOML syntax error"},
        // Outside gonio's domain: rejected before any work.
        {ok, "--set beam.theta_i=90",
         "key 'beam.theta_i': value 90 is out of range; allowed [0, 89.99]"},
        {ok, "--set ndf.type=student_t --set ndf.gamma=1.01",
         "key 'ndf.gamma': value 1.01 is outside gonio's domain [2, 1e6]"},
        {ok, "--set ndf.alpha=200", "key 'ndf.alpha': value 200 is out of range"},
        {ok, "--set material.type=dielectric --set material.eta=0",
         "key 'material.eta': value 0 is out of range"},
        {ok, "--set material.type=lambertian --set material.albedo=1.5",
         "key 'material.albedo': value 1.5 is out of range; allowed [0, 1]"},
        {ok, "--set trace.max_bounces=0", "key 'trace.max_bounces': value 0 is out of range"},
        {ok, "--set surface.size=4", "key 'surface.size': value 4 is out of range"},
        {ok, "--set trace.batches=1", "key 'trace.batches': value 1 is out of range"},
        {ok, "--set trace.target_error=0", "key 'trace.target_error': value 0 is out of range"},
        {ok, "--set trace.max_rays=100",
         "key 'trace.max_rays': applies only with trace.target_error"},
    };
    for (const Bad& b : cases) {
        CAPTURE(b.expect);
        write(d / "c.toml", b.text);
        const Run r = run_gonio(d, "model c.toml -o out.h5 " + b.extra_args);
        CHECK(r.code == 2);
        CHECK(r.err.find(b.expect) != std::string::npos);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK(r.out.empty());
        CHECK(files_in(d) == 1); // c.toml only
    }
    fs::remove_all(d);
}

TEST_CASE("gonio surface writes the height map and NDF comparison, then reuses the cache") {
    const fs::path d = fresh_dir("surface");
    write(d / "s.toml", "[ndf]\ntype = \"ggx\"\nalpha = 0.3\n[beam]\ntheta_i = 0\n"
                        "[surface]\nsize = 64\niterations = 20\n");
    const std::string args = "surface s.toml -o out.exr --cache-dir cache";
    const Run first = run_gonio(d, args);
    CHECK(first.code == 0);
    CHECK(first.out.find("generated with sliced-matching") != std::string::npos);
    CHECK(first.out.find("effective alpha") != std::string::npos);
    for (const char* f : {"out.exr", "out_ndf.exr", "out_ndf.csv"}) CHECK(fs::exists(d / f));
    const Run again = run_gonio(d, args);
    CHECK(again.code != 0); // outputs exist
    CHECK(again.err.find("out.exr: exists; pass --overwrite") != std::string::npos);
    const Run second = run_gonio(d, args + " --overwrite");
    CHECK(second.code == 0);
    CHECK(second.out.find("reused cached surface") != std::string::npos);
    const Run bad = run_gonio(d, "surface s.toml --set surface.generator=heitz -o x.exr");
    CHECK(bad.code == 2);
    CHECK(bad.err.find("key 'surface.generator': \"heitz\" makes Beckmann surfaces only") !=
          std::string::npos);
    const Run missing = run_gonio(d, "surface s.toml --set surface.input=nothere.exr -o x.exr");
    CHECK(missing.code == 2);
    CHECK(missing.err.find("key 'surface.input': cannot open ") != std::string::npos);
    CHECK(!fs::exists(d / "x.exr"));
    fs::remove_all(d);
}

TEST_CASE("gonio run traces, compares with the model, and writes the simulation") {
    const fs::path d = fresh_dir("run");
    write(d / "r.toml", "[ndf]\ntype = \"beckmann\"\nalpha = 0.5\n[beam]\ntheta_i = [0, 60]\n"
                        "[sensor]\ncells = 145\n[surface]\nsize = 64\niterations = 20\n"
                        "[trace]\nrays = 20000\norders = 3\n");
    const Run r = run_gonio(d, "run r.toml -o out.h5 --cache-dir cache");
    CHECK(r.code == 0);
    CHECK(r.out.find("rel_diff") != std::string::npos);
    const ResultSummary s = read_result_summary((d / "out.h5").string());
    REQUIRE(s.cases.size() == 1);
    for (const char* k : {"l1_albedo", "l2_albedo", "l2plus_albedo", "linf_albedo",
                          "model_l1_albedo", "ledger_absorbed", "ledger_capped", "ledger_lost",
                          "ledger_unaccounted", "l1_relative_difference", "l1_distance"}) {
        CAPTURE(k);
        REQUIRE(s.cases[0].albedos.count(k) == 1);
    }
    for (size_t i = 0; i < 2; ++i) { // a perfect mirror: everything is reflected
        CHECK(s.cases[0].albedos.at("linf_albedo")[i] == doctest::Approx(1.0).epsilon(1e-9));
        CHECK(s.cases[0].albedos.at("ledger_lost")[i] == 0.0);
    }
    {
        h5::silence_errors();
        h5::Handle f(H5Fopen((d / "out.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                     H5Fclose, "open");
        h5::Handle g(H5Gopen2(f, "r", H5P_DEFAULT), H5Gclose, "group");
        std::vector<hsize_t> dims;
        h5::read_doubles(g, "brdf", &dims);
        CHECK(dims ==
              std::vector<hsize_t>{2, 1, 4, 145, 1}); // theta_i, phi_i, order, cell, channel
    }
    const Run cmp = run_gonio(d, "compare out.h5");
    CHECK(cmp.code == 0);
    CHECK(cmp.out.find("sim_L1") != std::string::npos);
    CHECK(s.cases[0].albedos.count("transmitted_albedo") == 0); // opaque: no lower sensor
    {
        // A dielectric: the lower sensor and transmitted orders appear, R + T = 1.
        const Run diel = run_gonio(d, "run r.toml -o diel.h5 -q --cache-dir cache "
                                      "--set material.type=dielectric --set material.eta=1.5");
        REQUIRE(diel.code == 0);
        const ResultSummary t = read_result_summary((d / "diel.h5").string());
        const auto& a = t.cases[0].albedos;
        for (const char* k : {"t1_albedo", "t2_albedo", "t2plus_albedo", "transmitted_albedo"})
            REQUIRE(a.count(k) == 1);
        for (size_t i = 0; i < 2; ++i) {
            CHECK(a.at("linf_albedo")[i] + a.at("transmitted_albedo")[i] ==
                  doctest::Approx(1.0).epsilon(1e-9));
            CHECK(a.at("transmitted_albedo")[i] > 0.8);
        }
        h5::Handle f(H5Fopen((d / "diel.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                     H5Fclose, "open");
        h5::Handle g(H5Gopen2(f, "r", H5P_DEFAULT), H5Gclose, "group");
        std::vector<hsize_t> dims;
        h5::read_doubles(g, "btdf", &dims);
        CHECK(dims == std::vector<hsize_t>{2, 1, 4, 145, 1});
    }
    // Clean failures before any tracing: an unreadable surface file, an unwritable output.
    const Run nosurface =
        run_gonio(d, "run r.toml -o x.h5 --cache-dir cache --set surface.input=nothere.exr");
    CHECK(nosurface.code == 2);
    CHECK(nosurface.err.find("key 'surface.input': cannot open ") != std::string::npos);
    const Run unwritable = run_gonio(d, "run r.toml -o /nonexistent/dir/x.h5 --cache-dir cache");
    CHECK(unwritable.code == 1);
    CHECK(unwritable.err.find("/nonexistent/dir/x.h5") != std::string::npos);
    CHECK(!fs::exists(d / "x.h5"));
    fs::remove_all(d);
}

TEST_CASE("gonio run with diffuse facets: the IL model and the V-cavity beside the simulation") {
    const fs::path d = fresh_dir("lambert");
    write(d / "l.toml", "[ndf]\ntype = \"beckmann\"\nalpha = 0.5\n[beam]\ntheta_i = 30\n"
                        "[material]\ntype = \"lambertian\"\nalbedo = 0.8\n[sensor]\ncells = 145\n"
                        "[surface]\nsize = 64\niterations = 20\n[trace]\nrays = 10000\n");
    // Model L1 is the specular BRDF: asking for it with diffuse facets is refused up front.
    const Run refused =
        run_gonio(d, "run l.toml -o out.h5 --cache-dir cache --set model.models=\"l1\"");
    CHECK(refused.code == 2);
    CHECK(refused.err.find("key 'model.models'") != std::string::npos);
    CHECK(!fs::exists(d / "out.h5"));
    const Run r = run_gonio(
        d, "run l.toml -o out.h5 --cache-dir cache --set 'model.models=[\"il\", \"vcavity\"]'");
    CHECK(r.code == 0);
    const ResultSummary s = read_result_summary((d / "out.h5").string());
    REQUIRE(s.cases.size() == 1);
    const CaseSummary& c = s.cases[0];
    CHECK(c.models == std::vector<std::string>{"il", "vcavity"});
    CHECK(c.attributes.at("model_il_compared_with") == "l1");
    CHECK(c.attributes.at("model_vcavity_compared_with") == "linf");
    for (const char* name :
         {"model_il_albedo", "il_relative_difference", "il_distance", "model_vcavity_albedo",
          "model_vcavity_l1_albedo", "model_vcavity_l2plus_albedo", "vcavity_relative_difference",
          "vcavity_distance"})
        CHECK(c.albedos.count(name) == 1);
    // n = 1: Lambertian microfacets. Single scattering reflects less than every order; the
    // V-cavity keeps at most the albedo.
    const double il = c.albedos.at("model_il_albedo")[0],
                 vc = c.albedos.at("model_vcavity_albedo")[0];
    CHECK(il < vc);
    CHECK(vc <= 0.8 + 1e-12);
    CHECK(c.albedos.at("model_vcavity_l1_albedo")[0] +
              c.albedos.at("model_vcavity_l2plus_albedo")[0] ==
          doctest::Approx(vc).epsilon(1e-12));
    CHECK(c.albedos.at("linf_albedo")[0] <= 0.8 + 1e-12);
    CHECK(c.attributes.at("fresnel").find("lambertian(albedo=0.8") == 0);
    const Run cmp = run_gonio(d, "compare out.h5");
    CHECK(cmp.code == 0);
    CHECK(cmp.out.find("vcavity") != std::string::npos);
    CHECK(cmp.out.find("Linf") != std::string::npos);
    fs::remove_all(d);
}

TEST_CASE("a format-1 result file (gonio-result 1, lists as comma-joined strings) still reads") {
    const std::string path = std::string(GONIO_SOURCE_DIR) + "/tests/data/result_format1.h5";
    const ResultSummary s = read_result_summary(path);
    CHECK(s.format == 1);
    CHECK(s.attributes.at("file_format") == "gonio-result 1");
    CHECK(s.timings.empty());
    REQUIRE(s.cases.size() == 3);
    const CaseSummary& gold = s.cases[2];
    CHECK(gold.name == "gold_beckmann_aniso");
    CHECK(gold.cells == 145);
    CHECK(gold.channels == 3);
    CHECK(gold.wavelength_nm == std::vector<double>{650, 550, 450});
    CHECK(gold.models == std::vector<std::string>{"l1"});
    CHECK(gold.stop == std::vector<std::string>{"rays", "rays"});
    CHECK(gold.albedos.at("l1_albedo").size() == 6); // 2 theta_i x 1 phi_i x 3 channels
    CHECK(gold.albedos.count("l1_relative_difference_stderr") == 1);
    CHECK(gold.runs.at("rays").size() == 2);

    const fs::path d = fresh_dir("format1");
    const Run info = run_gonio(d, "info " + path + " --json");
    CHECK(info.code == 0);
    const nlohmann::json j = nlohmann::json::parse(info.out);
    CHECK(j.at("file_format") == "gonio-result 1");
    CHECK(j.at("cases")[0].at("models") == nlohmann::json::array({"l1"}));
    CHECK(j.at("cases")[0].at("incidences")[1].at("stop") == "rays");
    CHECK(j.at("cases")[0].at("incidences")[1].at("theta_i") == 60);
    const Run text = run_gonio(d, "info " + path);
    CHECK(text.code == 0);
    CHECK(text.out.find("case gold_beckmann_aniso") != std::string::npos);
    const Run compare = run_gonio(d, "compare " + path);
    CHECK(compare.code == 0);
    CHECK(compare.err.empty());
    // A header and one row per case, incidence, channel and model: (2 + 2 + 2 x 3) x 1.
    CHECK(std::count(compare.out.begin(), compare.out.end(), '\n') == 11);
    CHECK(compare.out.find("gold_beckmann_aniso") != std::string::npos);
    fs::remove_all(d);
}
