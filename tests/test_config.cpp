#include "core/config_error.h"
#include "gonio/config/config.h"
#include "heightfield/surface_generator.h"

#include <algorithm>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

using namespace gonio;

namespace {
const char* kBase = R"(seed = 7
[ndf]
type = "beckmann"
alpha = 0.5
[beam]
theta_i = [0, 45]
)";

// The error a config raises: message, line and key.
ConfigError error_of(const std::string& text, const std::vector<std::string>& sets = {}) {
    try {
        parse_config(text, "test.toml", sets);
    } catch (const ConfigError& e) {
        return e;
    }
    FAIL("the config was accepted: " << text);
    return ConfigError("", 0, "", "");
}

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}
} // namespace

TEST_CASE("the shipped quickstart config loads") {
    const Config cfg = load_config(std::string(GONIO_SOURCE_DIR) + "/configs/quickstart.toml");
    REQUIRE(cfg.cases.size() == 3);
    CHECK(cfg.seed == 1);
    CHECK(cfg.cases[0].name == "beckmann_0.5");
    CHECK(cfg.cases[0].theta_i_deg == std::vector<double>{0, 30, 60, 80});
    CHECK(cfg.cases[0].material.fresnel.channels() == 1);
    CHECK(cfg.cases[0].material.wavelengths_nm.empty());
    CHECK(cfg.cases[1].ndf->name() == "ggx");
    CHECK(cfg.cases[2].material.fresnel.channels() == 3);
    CHECK(cfg.cases[2].ndf->describe() == "beckmann(alpha_x=0.2, alpha_y=0.6)");
    CHECK(cfg.cases[2].sensor_cells == 3240);
}

TEST_CASE("a single-case config without [[case]] takes its name from the file") {
    const Config cfg = parse_config(kBase, "dir/my_case.toml");
    REQUIRE(cfg.cases.size() == 1);
    CHECK(cfg.cases[0].name == "my_case");
    CHECK(cfg.seed == 7);
    CHECK(cfg.cases[0].phi_i_deg == std::vector<double>{0});
    CHECK(cfg.cases[0].model.masking == MaskingForm::height_correlated);
}

TEST_CASE("sweeps: arrays and range tables") {
    const Config a =
        parse_config(std::string(kBase) + "[sensor]\ncells = 145\n", "t.toml",
                     {"beam.theta_i={start=0, stop=80, step=20}", "beam.phi_i=[0, 90]"});
    CHECK(a.cases[0].theta_i_deg == std::vector<double>{0, 20, 40, 60, 80});
    CHECK(a.cases[0].phi_i_deg == std::vector<double>{0, 90});
    const Config b = parse_config(kBase, "t.toml", {"beam.theta_i={start=10, stop=20, count=3}"});
    CHECK(b.cases[0].theta_i_deg == std::vector<double>{10, 15, 20});
}

TEST_CASE("cases inherit the top-level sections and override them") {
    const Config cfg = parse_config(std::string(kBase) + R"(
[[case]]
name = "a"
[[case]]
name = "b"
ndf = { type = "ggx", alpha_x = 0.1, alpha_y = 0.3 }
beam = { theta_i = 60 }
)",
                                    "t.toml");
    REQUIRE(cfg.cases.size() == 2);
    CHECK(cfg.cases[0].ndf->name() == "beckmann");
    CHECK(cfg.cases[0].theta_i_deg == std::vector<double>{0, 45});
    CHECK(cfg.cases[1].ndf->describe() == "ggx(alpha_x=0.1, alpha_y=0.3)");
    CHECK(cfg.cases[1].theta_i_deg == std::vector<double>{60});
}

TEST_CASE("--set overrides any key, by path, case index or case name") {
    const std::string two =
        std::string(kBase) + "[[case]]\nname = \"x_0.5\"\n[[case]]\nname = \"y\"\n";
    const Config a =
        parse_config(two, "t.toml",
                     {"ndf.alpha=0.25", "case.1.ndf.type=ggx", "case.x_0.5.beam.theta_i=[10, 20]"});
    CHECK(a.cases[0].ndf->describe() == "beckmann(alpha_x=0.25, alpha_y=0.25)");
    CHECK(a.cases[0].theta_i_deg == std::vector<double>{10, 20});
    CHECK(a.cases[1].ndf->name() == "ggx");
    CHECK(a.cases[1].theta_i_deg == std::vector<double>{0, 45});
    CHECK(contains(a.effective_toml, "0.25"));
    const ConfigError e = error_of(two, {"case.zz.ndf.alpha=1"});
    CHECK(contains(e.what(), "(--set)"));
    CHECK(contains(e.what(), "no element 'zz'"));
    CHECK(error_of(kBase, {"ndf.alpha"}).line() == 0);
}

TEST_CASE("config errors name the file, the line, the key and the allowed range") {
    SUBCASE("a misspelled key") {
        const ConfigError e =
            error_of("[ndf]\ntype = \"beckmann\"\nalhpa = 0.5\n[beam]\ntheta_i = 0\n");
        CHECK(e.line() == 3);
        CHECK(e.key() == "ndf.alhpa");
        CHECK(contains(e.what(),
                       "test.toml:3: key 'ndf.alhpa': unknown key (did you mean 'alpha'?)"));
    }
    SUBCASE("an unknown top-level key") {
        const ConfigError e = error_of("sede = 3\n" + std::string(kBase));
        CHECK(e.key() == "sede");
        CHECK(contains(e.what(), "did you mean 'seed'"));
    }
    SUBCASE("a wrong type") {
        const ConfigError e =
            error_of("[ndf]\ntype = \"ggx\"\nalpha = \"rough\"\n[beam]\ntheta_i = 0\n");
        CHECK(e.line() == 3);
        CHECK(contains(e.what(), "must be a number, got a string; allowed [1e-06, 100]"));
    }
    SUBCASE("alpha <= 0") {
        const ConfigError e = error_of(kBase, {"ndf.alpha=0"});
        CHECK(contains(e.what(), "key 'ndf.alpha': value 0 is out of range; allowed [1e-06, 100]"));
    }
    SUBCASE("theta_i outside [0, 90)") {
        const ConfigError e =
            error_of("[ndf]\ntype = \"ggx\"\nalpha = 0.2\n[beam]\ntheta_i = [0, 90]\n");
        CHECK(e.line() == 5);
        CHECK(
            contains(e.what(), "key 'beam.theta_i': value 90 is out of range; allowed [0, 89.99]"));
    }
    SUBCASE("a cell count < 1") {
        const ConfigError e = error_of(std::string(kBase) + "[sensor]\ncells = 0\n");
        CHECK(e.line() == 8);
        CHECK(
            contains(e.what(), "key 'sensor.cells': value 0 is out of range; allowed [1, 1e+07]"));
    }
    SUBCASE("a cell count that is not an integer") {
        CHECK(contains(error_of(std::string(kBase) + "[sensor]\ncells = 10.5\n").what(),
                       "must be an integer"));
    }
    SUBCASE("a value not in the allowed set") {
        const ConfigError e = error_of(kBase, {"ndf.type=gxx"});
        CHECK(contains(
            e.what(),
            "\"gxx\" is not allowed (did you mean \"ggx\"?); allowed: \"beckmann\", \"ggx\""));
    }
    SUBCASE("a missing required key") {
        const ConfigError e = error_of("[ndf]\ntype = \"ggx\"\n");
        CHECK(e.key() == "ndf.alpha");
        CHECK(contains(e.what(), "missing"));
    }
    SUBCASE("a beam only where the command needs one") {
        // gonio surface and gonio ndf need no incidence; gonio run and gonio model do.
        const Config cfg = parse_config("[ndf]\ntype = \"ggx\"\nalpha = 0.2\n", "t.toml");
        CHECK(cfg.cases[0].theta_i_deg.empty());
        try {
            cfg.require_beam("gonio run");
            FAIL("a run without incidences was accepted");
        } catch (const ConfigError& e) {
            CHECK(e.key() == "beam.theta_i");
            CHECK(contains(e.what(), "missing (gonio run needs an incidence sweep)"));
        }
    }
    SUBCASE("alpha and alpha_x together") {
        CHECK(contains(error_of(kBase, {"ndf.alpha_x=0.3"}).what(),
                       "either alpha or both alpha_x and alpha_y"));
    }
    SUBCASE("a key the case does not use") {
        const ConfigError e =
            error_of(std::string(kBase) + "[material]\ntype = \"mirror\"\nior = \"Au\"\n");
        CHECK(e.key() == "material.ior");
        CHECK(e.line() == 9);
        CHECK(contains(e.what(), "is not used by any case"));
    }
    SUBCASE("a missing refractive-index table") {
        const ConfigError e = error_of(std::string(kBase) +
                                       "[material]\ntype = \"conductor\"\nior = \"Unobtainium\"\n");
        CHECK(e.key() == "material.ior");
        CHECK(contains(e.what(), "Unobtainium.csv: cannot open refractive-index table"));
    }
    SUBCASE("a wavelength outside the table") {
        const ConfigError e = error_of(
            std::string(kBase) +
            "[material]\ntype = \"conductor\"\nior = \"Al\"\n[spectrum]\nwavelengths = [250]\n");
        CHECK(e.key() == "spectrum.wavelengths");
        CHECK(contains(e.what(), "allowed [300"));
    }
    SUBCASE("per-channel values that do not match the wavelengths") {
        const ConfigError e =
            error_of(std::string(kBase) + "[material]\ntype = \"dielectric\"\neta = [1.5, 1.6]\n");
        CHECK(contains(e.what(), "give one (achromatic) or one per wavelength (3)"));
    }
    SUBCASE("two cases with one name") {
        const ConfigError e =
            error_of(std::string(kBase) + "[[case]]\nname = \"a\"\n[[case]]\nname = \"a\"\n");
        CHECK(e.line() == 10);
        CHECK(contains(e.what(), "names two cases"));
    }
    SUBCASE("a TOML syntax error") {
        const ConfigError e = error_of("[ndf\ntype = 1\n");
        CHECK(e.line() == 1);
        CHECK(contains(e.what(), "TOML syntax error"));
    }
    SUBCASE("an unknown key in a range table") {
        CHECK(contains(error_of(kBase, {"beam.theta_i={start=0, stop=10, step=5, stpe=1}"}).what(),
                       "unknown key (allowed: start, stop, step, count)"));
    }
    SUBCASE("a missing config file") {
        try {
            load_config("/nonexistent/gonio.toml");
            FAIL("accepted a missing file");
        } catch (const ConfigError& e) {
            CHECK(contains(e.what(), "/nonexistent/gonio.toml: cannot open the config file"));
        }
    }
}

TEST_CASE("materials: channels follow what the material needs") {
    const Config c =
        parse_config(std::string(kBase) + "[material]\ntype = \"conductor\"\nior = \"Cu\"\n"
                                          "[spectrum]\nwavelengths = [700, 600, 500, 400]\n",
                     "t.toml");
    CHECK(c.cases[0].material.fresnel.channels() == 4);
    CHECK(c.cases[0].material.wavelengths_nm.size() == 4);
    const Config d = parse_config(
        std::string(kBase) + "[material]\ntype = \"dielectric\"\neta = 1.5\n", "t.toml");
    CHECK(d.cases[0].material.fresnel.channels() == 1);
    CHECK(d.cases[0].material.wavelengths_nm.empty());
    CHECK(d.cases[0].material.transmits);
    CHECK(d.cases[0].material.parts().size() == 1);
    const Config k = parse_config(
        std::string(kBase) + "[material]\ntype = \"conductor\"\nn = 0.2\nk = [3, 3.5, 4]\n",
        "t.toml");
    CHECK(k.cases[0].material.fresnel.channels() == 3);
    const Config dispersive = parse_config(
        std::string(kBase) + "[material]\ntype = \"dielectric\"\neta = [1.5, 1.52, 1.55]\n",
        "t.toml");
    CHECK(dispersive.cases[0].material.parts().size() == 3); // each channel refracts apart
}

TEST_CASE("surface config: defaults, values and errors") {
    const Config d = parse_config(kBase, "t.toml");
    CHECK(d.cases[0].surface.generator == &sliced_matching_generator());
    CHECK(d.cases[0].surface.size == 256);
    CHECK(d.cases[0].surface.target == MatchTarget::quantiles);
    CHECK(d.cases[0].surface.iterations == 100); // the exact marginal's default
    CHECK(d.cases[0].surface.threshold == 0.02);
    // The pool's path keeps R19's 500 iterations, and so does Algorithm 1.
    CHECK(parse_config(std::string(kBase) + "[surface]\ntarget = \"pool\"\n", "t.toml")
              .cases[0]
              .surface.iterations == 500);
    CHECK(d.cases[0].surface.seed == 7); // the run's seed
    const Config c =
        parse_config(std::string(kBase) + "[surface]\ngenerator = \"algorithm1\"\nsize = 64\n"
                                          "constraint = \"domes\"\nlattice = 4\n",
                     "t.toml");
    CHECK(c.cases[0].surface.generator == &algorithm1_generator());
    CHECK(c.cases[0].surface.iterations == 500);
    CHECK(c.cases[0].surface.constraint == Constraint::domes);
    CHECK(c.cases[0].surface.lattice == 4);
    auto err = [](const std::string& extra) {
        return std::string(error_of(std::string(kBase) + "[surface]\n" + extra).what());
    };
    CHECK(contains(err("generator = \"magic\"\n"),
                   "key 'surface.generator': \"magic\" is not allowed"));
    CHECK(contains(err("size = 4\n"),
                   "key 'surface.size': value 4 is out of range; allowed [8, 16384]"));
    CHECK(contains(err("threshold = 0\n"), "allowed (0, 1]"));
    CHECK(contains(err("stop_when_converged = 1\n"), "must be true or false"));
    CHECK(contains(err("size = 64\nconstraint = \"domes\"\nlattice = 40\n"), "allowed [1, 32]"));
    CHECK(
        contains(err("correlation_length = 4\n"), "key 'surface.correlation_length': is not used"));
    CHECK(contains(err("lattice = 4\n"), "key 'surface.lattice': is not used"));
    CHECK(contains(
        error_of(std::string(kBase) + "[surface]\ngenerator = \"heitz\"\n", {"ndf.type=ggx"})
            .what(),
        "\"heitz\" makes Beckmann surfaces only"));
    CHECK(
        contains(err("input = \"missing.exr\"\n"), "key 'surface.input': cannot open missing.exr"));
}

TEST_CASE("the generalised NDF family in a config: its shape keys, their ranges") {
    const Config cfg =
        parse_config(std::string(kBase), "t.toml", {"ndf.type=student_t", "ndf.gamma=3"});
    CHECK(cfg.cases[0].ndf->name() == "student_t");
    CHECK(cfg.cases[0].ndf->describe().find("gamma=3") != std::string::npos);
    const Config gt = parse_config(std::string(kBase), "t.toml",
                                   {"ndf.type=generalized_t", "ndf.p=1.5", "ndf.q=4"});
    CHECK(gt.cases[0].ndf->name() == "generalized_t");
    CHECK(contains(error_of(kBase, {"ndf.type=student_t", "ndf.gamma=1.2"}).what(),
                   "key 'ndf.gamma': value 1.2 is outside gonio's domain [2, 1e6]: below 2 "
                   "the slopes' variance is infinite"));
    CHECK(contains(error_of(kBase, {"ndf.type=student_t"}).what(), "key 'ndf.gamma': missing"));
    CHECK(contains(error_of(kBase, {"ndf.type=generalized_normal", "ndf.p=30"}).what(),
                   "key 'ndf.p': value 30 is out of range; allowed [0.5, 20]"));
    CHECK(contains(error_of(kBase, {"ndf.type=generalized_t", "ndf.p=1", "ndf.q=1"}).what(),
                   "p q must be >= 2"));
    // A shape key the type does not use is reported, like any unused key.
    CHECK(contains(error_of(kBase, {"ndf.gamma=3"}).what(), "ndf.gamma"));
}

TEST_CASE("curves, blends and mixtures in a config: nested distributions and their errors") {
    const std::string head = "seed = 1\n[beam]\ntheta_i = 60\n";
    const Config blend = parse_config(head + R"([ndf]
type = "blend"
x = { type = "ggx", alpha = 0.5 }
y = { type = "sinc", k = 6, floor = 0.05, points = 65 }
)",
                                      "t.toml");
    // Numbers in descriptions print shortest-round-trip (0.05, not 0.050000000000000003).
    CHECK(blend.cases[0].ndf->describe() == "blend(x: ggx(alpha_x=0.5, alpha_y=0.5); y: "
                                            "sinc(alpha_x=1, alpha_y=1, k=6, floor=0.05, "
                                            "points=65))");

    const Config mix = parse_config(head + R"([ndf]
type = "mixture"
components = [{ type = "beckmann", alpha = 0.1 }, { type = "gaussian", sigma = 20 }]
weights = [1, 3]
)",
                                    "t.toml");
    CHECK(mix.cases[0].ndf->name() == "mixture");
    CHECK(contains(mix.cases[0].ndf->describe(), "gaussian"));

    const Config pl = parse_config(head + R"([ndf]
type = "piecewise_linear"
theta = [0, 20, 45, 90]
value = [1, 0.8, 0.1, 0]
)",
                                   "t.toml");
    CHECK(contains(pl.cases[0].ndf->describe(), "theta_deg=[0, 20, 45, 90]"));
    const Config sampled = parse_config(head + R"([ndf]
type = "piecewise_linear"
points = 33
source = { type = "student_t", alpha = 0.4, gamma = 3 }
)",
                                        "t.toml");
    CHECK(contains(sampled.cases[0].ndf->describe(), "points=33 from student_t"));

    auto error = [&](const std::string& ndf) { return std::string(error_of(head + ndf).what()); };
    CHECK(contains(error("[ndf]\ntype = \"blend\"\nx = { type = \"ggx\", alpha_x = 0.2, alpha_y = "
                         "0.4 }\ny = { type = \"ggx\", alpha = 0.3 }\n"),
                   "key 'ndf.x': must be an isotropic curve"));
    CHECK(contains(error("[ndf]\ntype = \"blend\"\nx = { type = \"ggx\", alpa = 0.2 }\ny = { type "
                         "= \"ggx\", alpha = 0.3 }\n"),
                   "key 'ndf.x.alpa': unknown key (did you mean 'alpha'?)"));
    CHECK(contains(error("[ndf]\ntype = \"blend\"\nx = { type = \"ggx\", alpha = 0.2 }\n"),
                   "key 'ndf.y': missing"));
    CHECK(contains(error("[ndf]\ntype = \"mixture\"\ncomponents = [{ type = \"ggx\", alpha = 0.2 "
                         "}]\nweights = [1, 2]\n"),
                   "give one per component (1)"));
    CHECK(
        contains(error("[ndf]\ntype = \"mixture\"\ncomponents = [{ type = \"ggx\", alpha = 0 }]\n"),
                 "key 'ndf.components[0].alpha': value 0 is out of range"));
    CHECK(contains(error("[ndf]\ntype = \"piecewise_linear\"\ntheta = [0, 50, 40, 90]\nvalue = [1, "
                         "1, 1, 1]\n"),
                   "control angles must increase"));
    CHECK(contains(error("[ndf]\ntype = \"sinc\"\nk = 300\n"),
                   "key 'ndf.k': value 300 is out of range; allowed (0, 200]"));
    CHECK(contains(error("[ndf]\ntype = \"gaussian\"\nsigma = 120\n"), "key 'ndf.sigma'"));
    CHECK(contains(error("[ndf]\ntype = \"tabulated\"\nfile = \"nowhere.txt\"\n"),
                   "cannot open nowhere.txt"));
}

TEST_CASE("tabulated NDFs in a config: the file is found next to the config and checked") {
    const auto dir =
        std::filesystem::temp_directory_path() / ("gonio_cfg_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "good.txt") << "# isotropic: one column\n1\n0.5\n0.1\n0\n";
    std::ofstream(dir / "bad.txt") << "1 1\n1\n";
    const std::string config = (dir / "c.toml").string();
    std::ofstream(config)
        << "[beam]\ntheta_i = 30\n[ndf]\ntype = \"tabulated\"\nfile = \"good.txt\"\n";
    const Config cfg = load_config(config);
    CHECK(contains(cfg.cases[0].ndf->describe(), (dir / "good.txt").string()));
    CHECK(cfg.cases[0].ndf->name() == "tabulated");
    std::ofstream(config)
        << "[beam]\ntheta_i = 30\n[ndf]\ntype = \"tabulated\"\nfile = \"bad.txt\"\n";
    try {
        load_config(config);
        FAIL("a ragged table was accepted");
    } catch (const ConfigError& e) {
        CHECK(contains(e.what(), "key 'ndf.file'"));
        CHECK(contains(e.what(), "line 2 has 1 values"));
    }
    std::filesystem::remove_all(dir);
}

TEST_CASE("interfaced Lambertian materials: eta and albedo per channel, and their ranges") {
    const std::string head = "[ndf]\ntype = \"beckmann\"\nalpha = 0.5\n[beam]\ntheta_i = 30\n";
    const Config one = parse_config(
        head + "[material]\ntype = \"interfaced_lambertian\"\neta = 1.5\nalbedo = 0.6\n", "t.toml");
    CHECK(one.cases[0].channels() == 1);
    CHECK(one.cases[0].material.diffuse);
    const Config three = parse_config(head + "[material]\ntype = \"interfaced_lambertian\"\neta = "
                                             "1.5\nalbedo = [0.6, 0.3, 0.1]\n",
                                      "t.toml");
    CHECK(three.cases[0].channels() == 3);
    CHECK(three.cases[0].material.wavelengths_nm.size() == 3);
    CHECK(contains(error_of(head + "[material]\ntype = \"interfaced_lambertian\"\neta = 0.9\n"
                                   "albedo = 0.5\n")
                       .what(),
                   "key 'material.eta': value 0.9 is out of range; allowed [1, 100]"));
    CHECK(
        contains(error_of(head + "[material]\ntype = \"interfaced_lambertian\"\neta = [1.5, 1.4]\n"
                                 "albedo = 0.5\n")
                     .what(),
                 "give one (achromatic) or one per wavelength (3)"));
}

TEST_CASE("models per case: defaults by material, lists, what each needs, Ashikhmin's settings") {
    const std::string head = "[ndf]\ntype = \"beckmann\"\nalpha = 0.5\n[beam]\ntheta_i = 30\n";
    const std::string il =
        "[material]\ntype = \"interfaced_lambertian\"\neta = 1.5\nalbedo = 0.6\n";
    auto names = [](const Config& c) {
        std::vector<std::string> out;
        for (const ModelChoice& m : c.cases[0].model.models) out.push_back(m.name);
        return out;
    };
    CHECK(names(parse_config(head, "t.toml")) == std::vector<std::string>{"l1"});
    CHECK(names(parse_config(head + il, "t.toml")) == std::vector<std::string>{"il"});
    CHECK(names(parse_config(head + il, "t.toml", {"model.evaluate=false"})).empty());
    const Config both = parse_config(head + il +
                                         "[model]\nmodels = [\"il\", \"vcavity\"]\n"
                                         "vcavity_rays = 1000\nmasking = \"v-cavity\"\n",
                                     "t.toml");
    CHECK(names(both) == std::vector<std::string>{"il", "vcavity"});
    CHECK(contains(both.cases[0].model.models[1].description, "1000 paths per incidence"));
    CHECK(both.cases[0].model.models[1].compared_with == ModelTarget::linf);
    CHECK(both.cases[0].model.masking == MaskingForm::v_cavity);
    const Config vc = parse_config(head + "[model]\nmodels = \"vcavity\"\n", "t.toml");
    CHECK(contains(vc.cases[0].model.models[0].description, "1048576 paths")); // trace.rays
    // A model's own key without the model is a key no case uses.
    CHECK(contains(error_of(head + "[model]\nbody_points = 8\n").what(),
                   "key 'model.body_points': is not used"));
    CHECK(contains(error_of(head + il + "[model]\nmodels = \"l1\"\n").what(),
                   "key 'model.models': \"l1\" is a specular model"));
    CHECK(contains(error_of(head + "[model]\nmodels = \"il\"\n").what(),
                   "\"il\" needs lambertian or interfaced_lambertian facets, not mirror"));
    CHECK(contains(error_of(head + "[material]\ntype = \"dielectric\"\neta = 1.5\n"
                                   "[model]\nmodels = \"vcavity\"\n")
                       .what(),
                   "dielectric facets transmit"));
    CHECK(contains(error_of(head + "[model]\nmodels = [\"l1\", \"ashikmin\"]\n").what(),
                   "(did you mean \"ashikhmin\"?)"));
    CHECK(contains(error_of(head + "[model]\nmodels = [\"l1\", \"l1\"]\n").what(),
                   "names \"l1\" twice"));
    const Config a = parse_config(
        head + "[model]\nmodels = \"ashikhmin\"\nashikhmin = { distribution = \"velvet\", "
               "sigma = 0.4, correlation_width = 15, diffuse = \"metal\" }\n",
        "t.toml");
    CHECK(contains(a.cases[0].model.models[0].description, "velvet"));
    CHECK(a.cases[0].model.models[0].compared_with == ModelTarget::linf); // with a diffuse term
    const std::string ash = "[model]\nmodels = \"ashikhmin\"\n";
    CHECK(contains(error_of(head + ash + "ashikhmin = { diffuse = \"lambert\" }\n").what(),
                   "key 'model.ashikhmin.diffuse'"));
    CHECK(
        contains(error_of(head + ash + "ashikhmin = { rho = 1 }\n").what(), "model.ashikhmin.rho"));
    CHECK(contains(error_of(head + "[model]\nashikhmin = { rho_d = 1 }\n").what(),
                   "key 'model.ashikhmin': is not used"));
    CHECK(parse_config(head + "[model]\nmodels = \"pbrdf\"\n", "t.toml").cases[0].needs_surface());
}

TEST_CASE("docs/configuration.md's table is the declared keys (gonio keys --markdown)") {
    std::ifstream in(std::string(GONIO_SOURCE_DIR) + "/docs/configuration.md");
    REQUIRE(in);
    const std::string readme((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
    const std::string begin = "<!-- keys:begin (generated: build/gonio keys --markdown) -->\n";
    const std::string end = "<!-- keys:end -->";
    const size_t a = readme.find(begin), b = readme.find(end);
    REQUIRE(a != std::string::npos);
    REQUIRE(b != std::string::npos);
    // Out of date: regenerate the block with `build/gonio keys --markdown`.
    CHECK(readme.substr(a + begin.size(), b - a - begin.size()) == keys_markdown());
}

TEST_CASE("every declared key has a meaning, a range or choices, and reads back its default") {
    for (const KeyGroup& g : config_key_groups())
        for (const Key& k : g.keys) {
            CAPTURE(g.section + "." + k.name);
            CHECK(!k.meaning.empty());
            if (k.kind == KeyKind::number || k.kind == KeyKind::integer)
                CHECK(k.range.lo <= k.range.hi);
            if (k.number_default) CHECK(k.range.contains(*k.number_default));
            if (k.string_default && !k.choices.empty())
                CHECK(std::find(k.choices.begin(), k.choices.end(), *k.string_default) !=
                      k.choices.end());
        }
}
