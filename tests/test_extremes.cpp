// The extremes suite: every parameter pushed to the edge of gonio's domain (grazing and exactly
// normal light, a full turn of azimuth, mirror-smooth and extremely rough surfaces, Student-T
// tails from the heaviest to nearly Gaussian, index ratios 1, 1 + 1e-6 and 4, albedos 0 and 1,
// surfaces of 8^2 and 16^2, sensors of 1, 2 and 10^4 cells, a bounce cap of 1). In every case:
// nothing non-finite in the output, the ledger closes, albedos lie in [0, 1] within their errors,
// Lambda is finite and monotone, near-specular surfaces put the Fresnel value into the specular
// cell. What lies outside the domain is rejected up front (test_commands.cpp, config errors).
#include "core/hemisphere_integral.h"
#include "gonio/io/hdf5_handles.h"
#include "gonio/material/fresnel.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/microfacet_model.h"
#include "heightfield/ndf/ndf_family.h"
#include "sensor/beckers_sensor.h"
#include "tests/cli_harness.h"

#include <cmath>
#include <doctest/doctest.h>
#include <hdf5.h>
#include <map>

using namespace gonio;
using namespace gonio::test;

namespace {

// A distribution as a config's [ndf] table gives it.
std::string spec(const std::string& type, double alpha, double gamma = 2) {
    std::string s = "type = \"" + type + "\"\nalpha = " + std::to_string(alpha) + "\n";
    if (type == "student_t") s += "gamma = " + std::to_string(gamma) + "\n";
    return s;
}

// Every floating-point dataset under a group, by path.
std::map<std::string, std::vector<double>> all_datasets(hid_t file) {
    std::map<std::string, std::vector<double>> out;
    struct Visit {
        hid_t file;
        std::map<std::string, std::vector<double>>* out;
    } v{file, &out};
    H5Ovisit2(
        file, H5_INDEX_NAME, H5_ITER_INC,
        [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
            auto* v = static_cast<Visit*>(data);
            if (info->type != H5O_TYPE_DATASET) return 0;
            h5::Handle d(H5Dopen2(v->file, name, H5P_DEFAULT), H5Dclose, "open dataset");
            h5::Handle t(H5Dget_type(d), H5Tclose, "dataset type");
            if (H5Tget_class(t) != H5T_FLOAT) return 0;
            h5::Handle space(H5Dget_space(d), H5Sclose, "dataspace");
            std::vector<double> values(size_t(H5Sget_simple_extent_npoints(space)));
            h5::check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
                      "read");
            (*v->out)[name] = std::move(values);
            return 0;
        },
        &v, H5O_INFO_BASIC);
    return out;
}

const char* kExtremes = R"(seed = 3
[beam]
theta_i = [0, 60, 89, 89.99]
phi_i = 7
[sensor]
cells = 100
[surface]
size = 32
iterations = 20
[trace]
rays = 1024
[[case]]
name = "grazing_full_turn"
ndf = { type = "beckmann", alpha = 0.5 }
beam = { theta_i = [0, 89, 89.9, 89.99], phi_i = [0, 360] }
[[case]]
name = "mirror_1e-4"
ndf = { type = "beckmann", alpha = 1e-4 }
[[case]]
name = "conductor_1e-3"
ndf = { type = "beckmann", alpha = 1e-3 }
material = { type = "conductor", n = 0.21, k = 3.272 }
[[case]]
name = "beckmann_3"
ndf = { type = "beckmann", alpha = 3 }
[[case]]
name = "ggx_5"
ndf = { type = "ggx", alpha = 5 }
[[case]]
name = "student_t_1e4"
ndf = { type = "student_t", alpha = 0.5, gamma = 1e4 }
[[case]]
name = "index_1"
ndf = { type = "beckmann", alpha = 0.3 }
material = { type = "dielectric", eta = 1.0 }
[[case]]
name = "index_1_plus_1e-6"
ndf = { type = "beckmann", alpha = 1e-4 }
material = { type = "dielectric", eta = 1.000001 }
[[case]]
name = "index_4"
ndf = { type = "beckmann", alpha = 0.5 }
material = { type = "dielectric", eta = 4 }
[[case]]
name = "albedo_0"
ndf = { type = "beckmann", alpha = 0.5 }
material = { type = "interfaced_lambertian", eta = 1.5, albedo = 0 }
model = { models = ["il", "vcavity"] }
[[case]]
name = "albedo_1"
ndf = { type = "beckmann", alpha = 0.5 }
material = { type = "lambertian", albedo = 1 }
model = { models = ["il", "vcavity"] }
[[case]]
name = "surface_8"
ndf = { type = "beckmann", alpha = 0.5 }
surface = { size = 8 }
[[case]]
name = "surface_16_one_cell"
ndf = { type = "beckmann", alpha = 0.5 }
surface = { size = 16 }
sensor = { cells = 1 }
[[case]]
name = "two_cells"
ndf = { type = "beckmann", alpha = 0.5 }
sensor = { cells = 2 }
[[case]]
name = "cells_1e4_cap_1"
ndf = { type = "beckmann", alpha = 0.5 }
sensor = { cells = 10000 }
trace = { max_bounces = 1 }
)";

} // namespace

TEST_CASE("extremes: Lambda is finite, non-negative and monotone in theta up to 89.999 degrees") {
    for (const std::string& s :
         {spec("beckmann", 1e-4), spec("beckmann", 1e-3), spec("beckmann", 3), spec("beckmann", 5),
          spec("ggx", 1e-4), spec("ggx", 1e-3), spec("ggx", 3), spec("ggx", 5),
          spec("student_t", 0.5, 2), spec("student_t", 0.5, 1e4), spec("student_t", 1e-4, 1e4),
          spec("student_t", 5, 2)}) {
        const auto ndf = ndf_from_toml(s);
        CAPTURE(ndf->describe());
        for (double phi : {0.0, 1.0, 3.0}) {
            double last = 0;
            for (double deg = 0; deg < 89.9995; deg += deg < 89 ? 0.5 : 0.001) {
                const double l = ndf->lambda(spherical_direction(radians(deg), phi));
                CAPTURE(deg);
                REQUIRE(std::isfinite(l));
                CHECK(l >= 0);
                // Round-off allowed (and underflow: 1 + Lambda cannot tell 1e-67 from 0).
                CHECK(l >= last * (1 - 1e-12) - 1e-15);
                last = l;
            }
        }
    }
}

TEST_CASE("extremes: Model L1 at grazing incidence against a brute-force half-vector integral") {
    const BeckersSensor sensor(100);
    for (const std::string& s : {spec("beckmann", 3), spec("ggx", 5), spec("ggx", 0.3)}) {
        const auto ndf = ndf_from_toml(s);
        const MicrofacetModel model(*ndf, FresnelTerm::mirror(), MaskingForm::height_correlated);
        for (double deg : {89.0, 89.99}) {
            CAPTURE(ndf->describe());
            CAPTURE(deg);
            const Vec3 wi = spherical_direction(radians(deg), 0.0);
            // albedo = int f cos(theta_o) dw_o, with dw_o = 4 (i.h) dw_h.
            auto g = [&](const Vec3& h) {
                const double ih = dot(wi, h);
                const Vec3 o = 2 * ih * h - wi;
                if (ih <= 0 || o.z <= 0) return 0.0;
                double f;
                model.eval_cosine(wi, o, &f);
                return 4 * ih * f;
            };
            const double reference = hemisphere_integral(g, 0.01, &wi, 1e-10);
            double cells = 0;
            for (double e : model_cell_energy(model, wi, sensor, CellQuadrature{})) cells += e;
            CHECK(cells == doctest::Approx(reference).epsilon(1e-6)); // the cells' tolerance
        }
    }
}

TEST_CASE(
    "extremes: finite output, closed ledger, albedos in [0, 1], Fresnel in the specular cell") {
    const fs::path d = fresh_dir("extremes");
    write(d / "extremes.toml", kExtremes);
    const Run r = run_gonio(d, "run extremes.toml -o extremes.h5 -q");
    REQUIRE_MESSAGE(r.code == 0, r.err);
    h5::Handle file(H5Fopen((d / "extremes.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                    "open extremes.h5");
    const auto data = all_datasets(file);
    REQUIRE(data.size() > 100);
    // Nothing non-finite, anywhere.
    for (const auto& [name, values] : data) {
        size_t bad = 0;
        for (double v : values) bad += !std::isfinite(v);
        CAPTURE(name);
        CHECK(bad == 0);
    }
    auto get = [&](const std::string& path) -> const std::vector<double>& {
        const auto it = data.find(path);
        REQUIRE_MESSAGE(it != data.end(), path);
        return it->second;
    };
    const std::vector<std::string> cases{
        "grazing_full_turn", "mirror_1e-4", "conductor_1e-3",      "beckmann_3", "ggx_5",
        "student_t_1e4",     "index_1",     "index_1_plus_1e-6",   "index_4",    "albedo_0",
        "albedo_1",          "surface_8",   "surface_16_one_cell", "two_cells",  "cells_1e4_cap_1"};
    for (const std::string& c : cases) {
        CAPTURE(c);
        // The ledger closes: nothing lost, nothing unaccounted beyond round-off.
        for (double v : get(c + "/ledger_unaccounted")) CHECK(std::abs(v) < 1e-12);
        for (double v : get(c + "/ledger_lost")) CHECK(v == 0);
        // Albedos in [0, 1] within 4 standard errors (models: within their tolerance).
        for (const auto& [name, values] : data) {
            if (name.rfind(c + "/", 0) != 0 || name.size() < 7 ||
                name.compare(name.size() - 7, 7, "_albedo") != 0)
                continue;
            const auto err = data.find(name + "_stderr");
            for (size_t k = 0; k < values.size(); ++k) {
                const double e = err != data.end() ? 4 * err->second[k] : 1e-6;
                CAPTURE(name);
                CHECK(values[k] >= -e - 1e-12);
                CHECK(values[k] <= 1 + e + 1e-12);
            }
        }
    }
    // Near-specular: the whole power of the first order in the specular cell, with the Fresnel
    // value, in the simulation and in Model L1 (theta_i 0, 60 and 89; at 89.99 degrees even
    // alpha = 1e-4 is masked). The dielectrics choose between reflection and refraction at
    // random: a Fresnel value of 1e-6 is rarely drawn with 10^3 rays, so its error is at least
    // the binomial one.
    const BeckersSensor sensor(100);
    struct Specular {
        const char* name;
        std::function<double(double)> reflect, transmit; // of cos(theta_i)
        bool all_orders; // index 1: a grazing ray crosses the rough interface many times
    };
    const std::complex<double> gold{0.21, 3.272};
    const Specular near_specular[] = {
        {"mirror_1e-4", [](double) { return 1.0; }, nullptr, false},
        {"conductor_1e-3", [&](double c) { return fresnel_conductor(c, gold); }, nullptr, false},
        {"index_1_plus_1e-6", [](double c) { return fresnel_dielectric(c, 1.000001); },
         [](double c) { return 1 - fresnel_dielectric(c, 1.000001); }, false},
        {"index_1", [](double) { return 0.0; }, [](double) { return 1.0; }, true},
    };
    const size_t cells = 100;
    for (const Specular& s : near_specular) {
        const std::string n = s.name;
        const std::vector<double>& rays = get(n + "/rays");
        const std::string up = n + (s.all_orders ? "/brdf_linf" : "/brdf_l1");
        const std::string down = n + (s.all_orders ? "/btdf_tinf" : "/btdf_t1");
        const std::vector<double>&brdf = get(up), &brdf_err = get(up + "_stderr");
        const std::vector<double>& model = get(n + "/model_l1_energy");
        const size_t nc = brdf.size() / (4 * cells); // channels (all alike here)
        const double thetas[] = {0, 60, 89};
        for (size_t t = 0; t < 3; ++t) {
            CAPTURE(n);
            CAPTURE(thetas[t]);
            const Vec3 wi = spherical_direction(radians(thetas[t]), radians(7.0));
            const int cell = sensor.lookup({-wi.x, -wi.y, wi.z});
            const double omega = sensor.cell(cell).projected_solid_angle;
            const size_t i = (t * cells + size_t(cell)) * nc; // channel 0
            const double F = s.reflect(wi.z);
            const double binomial = s.transmit ? std::sqrt(F * (1 - F) / rays[t]) : 0.0;
            CHECK(std::abs(brdf[i] * omega - F) <=
                  4 * std::max(brdf_err[i] * omega, binomial) + 1e-9);
            CHECK(model[i] == doctest::Approx(F).epsilon(1e-5));
            if (s.transmit) {
                const std::vector<double>&btdf = get(down), &btdf_err = get(down + "_stderr");
                CHECK(std::abs(btdf[i] * omega - s.transmit(wi.z)) <=
                      4 * std::max(btdf_err[i] * omega, binomial) + 1e-9);
            }
        }
    }
    fs::remove_all(d);
}
