// `gonio export`: every format read back by a reader written here from its specification, round
// trips against the result file, physical checks (the RGL rule at cell centres, importance
// sampling through the RGL file against the L-infinity albedo, MERL symmetry and reciprocity, a
// Lambertian surface's near-constant BRDF, a near-mirror's concentration), and the refusals.
#include "core/random.h"
#include "gonio/export/export.h"
#include "gonio/table/bsdf_table.h"
#include "gonio/table/result_case.h"
#include "sensor/beckers_sensor.h"
#include "tests/export_fixtures.h"
#include "tests/rgl_reader.h"

#include <algorithm>
#include <cstdint>
#include <doctest/doctest.h>
#include <fstream>
#include <sstream>

using namespace gonio;
using namespace gonio::test;

namespace {

std::string export_to(const std::string& input, const std::string& format, const fs::path& out,
                      const std::string& extra = "") {
    const Run r =
        run_gonio(out.parent_path(), "export '" + input + "' --format " + format + " -o '" +
                                         out.string() + "' --overwrite " + extra);
    INFO(r.err);
    REQUIRE(r.code == 0);
    return r.out;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// MERL .binary read from its specification: three int32, then R, G, B blocks of float64 scaled by
// 1/1500, 1.15/1500, 1.66/1500; index phi_d + 180 theta_d + 16200 theta_h.
struct Merl {
    std::int32_t dims[3];
    std::vector<double> data;
    double at(int channel, int th, int td, int pd) const {
        static const double scale[3] = {1.0 / 1500, 1.15 / 1500, 1.66 / 1500};
        const double v = data[size_t(channel) * 1458000 + (size_t(th) * 90 + td) * 180 + pd];
        return v < 0 ? -1 : v * scale[channel];
    }
};
Merl read_merl(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    Merl m;
    in.read(reinterpret_cast<char*>(m.dims), 12);
    m.data.resize(3 * 1458000);
    in.read(reinterpret_cast<char*>(m.data.data()), std::streamsize(m.data.size() * 8));
    REQUIRE(in.gcount() == std::streamsize(m.data.size() * 8));
    return m;
}

std::vector<std::vector<std::string>> read_csv(const fs::path& p,
                                               std::vector<std::string>* comments) {
    std::ifstream in(p);
    std::vector<std::vector<std::string>> rows;
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("#", 0) == 0) {
            if (comments) comments->push_back(line);
            continue;
        }
        std::vector<std::string> cells;
        std::stringstream ss(line);
        std::string c;
        while (std::getline(ss, c, ',')) cells.push_back(c);
        if (!line.empty() && line.back() == ',') cells.push_back("");
        rows.push_back(cells);
    }
    return rows;
}

} // namespace

TEST_CASE(
    "export rgl: the file read by the specification's rule matches the table at cell centres") {
    const std::string input = gold_table();
    const fs::path dir = fresh_dir("export_rgl");
    export_to(input, "rgl", dir / "gold.bsdf");
    const RglBsdf rgl((dir / "gold.bsdf").string());
    const ResultCase c = read_result_case(input, "");
    const TableData d = table_data(c, TableOrder::linf);
    const BeckersSensor sensor(d.cells);
    // Round trip of the parameter fields.
    const auto& theta = rgl.field("theta_i").values;
    REQUIRE(theta.size() == d.theta_i_deg.size());
    for (size_t k = 0; k < theta.size(); ++k)
        CHECK(theta[k] == doctest::Approx(radians(d.theta_i_deg[k])).epsilon(1e-6));
    CHECK(rgl.field("phi_i").values.size() == 1);
    CHECK(rgl.isotropic());
    CHECK(rgl.field("jacobian").values == std::vector<double>{1});
    CHECK(rgl.field("description").text().find("gold") != std::string::npos);
    const auto& wl = rgl.field("wavelengths").values;
    CHECK(wl == std::vector<double>{450, 550, 650});
    // Every swept incidence, every bright cell, every channel: f from the file against the
    // tabulated BSDF it was made from (and, for the record, against the raw cell averages, whose
    // Monte Carlo noise the table's symmetry halves).
    const BsdfTable table(d);
    std::vector<double> errors, raw_errors;
    for (size_t ti = 0; ti < d.theta_i_deg.size(); ++ti) {
        const Vec3 wp = spherical_direction(radians(d.theta_i_deg[ti]), 0.0);
        for (int ch = 0; ch < 3; ++ch) {
            double peak = 0;
            for (int cell = 0; cell < d.cells; ++cell)
                peak = std::max(peak, d.f[(ti * d.cells + cell) * 3 + ch]);
            for (int cell = 0; cell < d.cells; ++cell) {
                const double raw = d.f[(ti * d.cells + cell) * 3 + ch];
                if (raw < 0.1 * peak) continue;
                const Vec3 wq = sensor.cell(cell).center;
                double f[3];
                table.eval(wp, wq, f);
                // The file's spectra are in increasing wavelength: 450, 550, 650 (as stored).
                const double file = rgl.eval(wp, wq)[ch] / wq.z;
                errors.push_back(std::abs(file / f[ch] - 1));
                raw_errors.push_back(std::abs(file / raw - 1));
            }
        }
    }
    const double m = median(errors);
    MESSAGE("median relative error over " << errors.size() << " bright cells: " << m
                                          << " (against the raw cells: " << median(raw_errors)
                                          << ")");
    CHECK(m <= 0.10);
}

TEST_CASE("export rgl: importance sampling through the file returns the L-infinity albedo") {
    const std::string input = gold_table();
    const fs::path dir = fresh_dir("export_rgl_sampling");
    export_to(input, "rgl", dir / "gold.bsdf");
    const RglBsdf rgl((dir / "gold.bsdf").string());
    const ResultCase c = read_result_case(input, "");
    const std::vector<double> albedo = c.read_albedo("linf_albedo"),
                              error = c.read_albedo("linf_albedo_stderr");
    Rng rng{21, 4};
    const int n = 100000;
    for (size_t ti : {size_t(0), size_t(6), size_t(12), size_t(15)}) { // 0, 30, 60, 75 degrees
        const Vec3 wp = spherical_direction(radians(5.0 * double(ti)), 0.0);
        std::vector<double> sum(3, 0.0), sum2(3, 0.0);
        for (int k = 0; k < n; ++k) {
            const auto s = rgl.sample(wp, rng.uniform(), rng.uniform());
            for (int ch = 0; ch < 3; ++ch) {
                sum[ch] += s.weight[ch];
                sum2[ch] += s.weight[ch] * s.weight[ch];
            }
        }
        for (int ch = 0; ch < 3; ++ch) {
            const double mean = sum[ch] / n;
            const double mc = std::sqrt((sum2[ch] / n - mean * mean) / n);
            const double expected = albedo[ti * 3 + ch];
            MESSAGE("theta_i " << 5 * ti << " channel " << ch << ": " << mean << " +- " << mc
                               << " against " << expected << " +- " << error[ti * 3 + ch]);
            CHECK(std::abs(mean / expected - 1) <= 0.03);
            CHECK(mc < 0.005 * expected); // the sampler follows f cos: the weights barely vary
        }
    }
}

TEST_CASE("export rgl: an anisotropic sweep over the full turn spans [-pi, pi]") {
    const std::string input =
        fixture("aniso", sweep_config("{ type = \"beckmann\", alpha_x = 0.2, alpha_y = 0.5 }",
                                      "{ type = \"mirror\" }", 800, 65536, 128, "[0, 90, 180, 270]",
                                      10, 80));
    const fs::path dir = fresh_dir("export_rgl_aniso");
    export_to(input, "rgl", dir / "aniso.bsdf");
    const RglBsdf rgl((dir / "aniso.bsdf").string());
    CHECK_FALSE(rgl.isotropic());
    const auto& phi = rgl.field("phi_i").values;
    REQUIRE(phi.size() == 5);
    CHECK(phi.front() == doctest::Approx(-kPi));
    CHECK(phi.back() == doctest::Approx(kPi));
    const ResultCase c = read_result_case(input, "");
    const TableData d = table_data(c, TableOrder::linf);
    const BeckersSensor sensor(d.cells);
    const BsdfTable table(d);
    std::vector<double> errors;
    for (size_t ti = 1; ti < d.theta_i_deg.size(); ++ti)
        for (size_t pj = 0; pj < 4; ++pj) {
            const Vec3 wp =
                spherical_direction(radians(d.theta_i_deg[ti]), radians(d.phi_i_deg[pj]));
            const double* f = d.f.data() + (ti * 4 + pj) * d.cells;
            const double peak = *std::max_element(f, f + d.cells);
            for (int cell = 0; cell < d.cells; ++cell)
                if (f[cell] >= 0.1 * peak) {
                    const Vec3 wq = sensor.cell(cell).center;
                    double t = 0;
                    table.eval(wp, wq, &t);
                    errors.push_back(std::abs(rgl.eval(wp, wq)[0] / wq.z / t - 1));
                }
        }
    const double m = median(errors);
    MESSAGE("median relative error over " << errors.size() << " bright cells: " << m);
    CHECK(m <= 0.10);
    export_to(input, "rgl", dir / "aniso_rgb.bsdf", "--rgb");
    const RglBsdf rgb((dir / "aniso_rgb.bsdf").string());
    CHECK(rgb.channels() == 3);
    CHECK(rgb.field("rgb").shape == std::vector<std::uint64_t>{5, 9, 3, 64, 64});
}

TEST_CASE("export merl: layout, symmetry in phi_d, reciprocity, and the horizon") {
    const std::string input = gold_table();
    const fs::path dir = fresh_dir("export_merl");
    export_to(input, "merl", dir / "gold.binary");
    CHECK(fs::file_size(dir / "gold.binary") == 34992012u);
    const Merl m = read_merl(dir / "gold.binary");
    CHECK(m.dims[0] == 90);
    CHECK(m.dims[1] == 90);
    CHECK(m.dims[2] == 180);
    // Symmetric in phi_d (phi_d and pi - phi_d: the mirror image and reciprocity).
    int compared = 0, invalid = 0;
    for (int th = 0; th < 90; th += 7)
        for (int td = 0; td < 90; td += 3)
            for (int pd = 0; pd < 90; ++pd)
                for (int ch = 0; ch < 3; ++ch) {
                    const double a = m.at(ch, th, td, pd), b = m.at(ch, th, td, 179 - pd);
                    if (a < 0 || b < 0) {
                        CHECK((a < 0) == (b < 0));
                        ++invalid;
                        continue;
                    }
                    REQUIRE(a == doctest::Approx(b).epsilon(1e-9));
                    ++compared;
                }
    CHECK(compared > 10000);
    CHECK(invalid > 0); // below the horizon
    // theta_d = 0 is the retro-reflection... the bin at theta_h = theta_d = 0 is valid, positive.
    for (int ch = 0; ch < 3; ++ch) CHECK(m.at(ch, 0, 0, 0) > 0);
    // Reciprocity where the data are: the table's lobe at wi seen from wo against its lobe at wo
    // seen from wi, between swept incidences, within their errors.
    const ResultCase c = read_result_case(input, "");
    const TableData d = table_data(c, TableOrder::linf);
    const BsdfTable table(d);
    const BeckersSensor sensor(d.cells);
    std::vector<double> z;
    for (int a = 2; a < 14; ++a)
        for (int b = a + 1; b < 14; ++b)
            for (double phi : {0.5, 1.5, 2.5, 3.0}) {
                const Vec3 wi = spherical_direction(radians(5.0 * a), 0);
                const Vec3 wo = spherical_direction(radians(5.0 * b), phi);
                double f1[3], f2[3];
                table.eval(wi, wo, f1);
                table.eval(wo, wi, f2);
                // Errors: the stderr of the cell at each end (the interpolated lobes average
                // several cells: this overstates their noise a little).
                const double e1 = d.f_stderr[(size_t(a) * d.cells + sensor.lookup(wo)) * 3 + 1];
                const double e2 =
                    d.f_stderr[(size_t(b) * d.cells +
                                sensor.lookup(spherical_direction(radians(5.0 * a), -phi))) *
                                   3 +
                               1];
                if (e1 > 0 && e2 > 0) z.push_back(std::abs(f1[1] - f2[1]) / std::hypot(e1, e2));
            }
    const double mz = median(z);
    // A normal deviate's median |z| is 0.67; interpolation between swept incidences adds a
    // little, a tracer that breaks reciprocity is off by many standard errors.
    MESSAGE("reciprocity: median |difference| " << mz << " standard errors over " << z.size()
                                                << " pairs");
    CHECK(z.size() > 200);
    CHECK(mz < 1.5);
}

TEST_CASE("export merl: a Lambertian-facet surface gives a near-constant BRDF") {
    const std::string input = fixture(
        "lambert", sweep_config("{ type = \"beckmann\", alpha = 0.05 }",
                                "{ type = \"lambertian\", albedo = 0.8 }", 400, 1048576, 64));
    const fs::path dir = fresh_dir("export_merl_lambert");
    export_to(input, "merl", dir / "lambert.binary");
    const Merl m = read_merl(dir / "lambert.binary");
    std::vector<double> ratio;
    for (int th = 0; th < 90; th += 3)
        for (int td = 0; td < 90; td += 3)
            for (int pd = 0; pd < 180; pd += 5) {
                const double v = m.at(1, th, td, pd);
                if (v < 0) continue;
                // Only where both directions are above 60 degrees from the horizon... at most 60
                // degrees from the normal: the rim of a rough Lambertian surface is darker.
                const double theta_h = std::pow((th + 0.5) / 90, 2) * kPi / 2;
                const double theta_d = (td + 0.5) * kPi / 180;
                if (theta_h + theta_d > radians(60)) continue;
                ratio.push_back(v / (0.8 / kPi));
            }
    std::sort(ratio.begin(), ratio.end());
    const double lo = ratio[ratio.size() / 100], mid = ratio[ratio.size() / 2],
                 hi = ratio[ratio.size() * 99 / 100];
    MESSAGE("f / (0.8 / pi): 1st percentile " << lo << ", median " << mid << ", 99th " << hi);
    // A smooth Lambertian-facet surface is Lambertian up to its multiple scattering (a little
    // energy lost between facets) and the cells' noise (4% per cell at 2^20 rays on 400 cells).
    CHECK(mid == doctest::Approx(1.0).epsilon(0.05));
    CHECK(lo > 0.85);
    CHECK(hi < 1.15);
}

TEST_CASE("export: a near-mirror (alpha 1e-3) concentrates at the mirror direction") {
    const std::string input =
        fixture("mirror", sweep_config("{ type = \"beckmann\", alpha = 0.001 }",
                                       "{ type = \"mirror\" }", 1200, 65536, 64));
    const fs::path dir = fresh_dir("export_mirror");
    export_to(input, "rgl", dir / "mirror.bsdf");
    export_to(input, "merl", dir / "mirror.binary");
    const RglBsdf rgl((dir / "mirror.bsdf").string());
    const double cell = std::sqrt(kTwoPi / 1200); // the sensor's angular resolution
    Rng rng{5, 5};
    for (double t : {10.0, 40.0, 70.0}) {
        const Vec3 wp = spherical_direction(radians(t), 0);
        const Vec3 mirror = reflect(wp, {0, 0, 1});
        int near = 0;
        double albedo = 0;
        const int n = 20000;
        for (int k = 0; k < n; ++k) {
            const auto s = rgl.sample(wp, rng.uniform(), rng.uniform());
            albedo += s.weight[0] / n;
            near += s.pdf > 0 && angle_between(s.wq, mirror) < 2 * cell;
        }
        MESSAGE("theta_i " << t << ": " << near << " of " << n << " samples within 2 cells, albedo "
                           << albedo);
        CHECK(near > 0.95 * n);
        CHECK(albedo == doctest::Approx(1.0).epsilon(0.03)); // a perfect mirror loses nothing
        // The file's f cos peaks within a cell of the mirror direction (the sensor cannot say
        // where inside its cell the mirror lies) and falls off beyond.
        double peak = 0, peak_at = 0;
        for (double off = -4; off <= 4; off += 0.05) {
            const double v = rgl.eval(wp, spherical_direction(radians(t) + off * cell, kPi))[0];
            if (v > peak) peak = v, peak_at = off;
        }
        CHECK(std::abs(peak_at) <= 1.0);
        for (double off : {-3.5, 3.5})
            CHECK(rgl.eval(wp, spherical_direction(radians(t) + (peak_at + off) * cell, kPi))[0] <
                  0.05 * peak);
    }
    const Merl m = read_merl(dir / "mirror.binary");
    // Over theta_h the MERL values fall off within the cells' size from theta_h = 0.
    const double at_peak = m.at(0, 0, 30, 90);
    const int far = int(std::ceil(std::sqrt(3 * cell / (kPi / 2)) * 90)); // theta_h = 3 cells
    CHECK(at_peak > 0);
    CHECK(m.at(0, std::min(far, 89), 30, 90) < 0.05 * at_peak);
}

TEST_CASE("export astm: rows per incidence and cell centre round-trip the file") {
    const std::string input = gold_table();
    const fs::path dir = fresh_dir("export_astm");
    export_to(input, "astm", dir / "gold.astm", "--orders l1");
    std::ifstream in(dir / "gold.astm");
    std::string line;
    long long points = -1;
    std::vector<std::string> vars;
    while (std::getline(in, line)) {
        if (line.rfind("NUM_POINTS ", 0) == 0) points = std::stoll(line.substr(11));
        if (line.rfind("VARS ", 0) == 0) {
            std::stringstream ss(line.substr(5));
            std::string v;
            while (std::getline(ss, v, ',')) vars.push_back(v);
            break;
        }
    }
    CHECK(vars == std::vector<std::string>{"theta_i", "phi_i", "theta_s", "phi_s", "450nm", "550nm",
                                           "650nm"});
    const ResultCase c = read_result_case(input, "");
    const TableData d = table_data(c, TableOrder::l1);
    const BeckersSensor sensor(d.cells);
    long long rows = 0;
    while (std::getline(in, line)) {
        std::vector<double> v;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
        REQUIRE(v.size() == 7);
        const size_t incidence = size_t(rows) / size_t(d.cells), k = size_t(rows) % size_t(d.cells);
        REQUIRE(v[0] == radians(d.theta_i_deg[incidence]));
        REQUIRE(v[2] == sensor.cell(int(k)).theta_center);
        REQUIRE(v[3] == sensor.cell(int(k)).phi_center);
        for (int ch = 0; ch < 3; ++ch)
            REQUIRE(v[4 + ch] == d.f[(incidence * d.cells + k) * 3 + ch]);
        ++rows;
    }
    CHECK(rows == points);
    CHECK(rows == (long long)(d.theta_i_deg.size()) * d.cells);
}

TEST_CASE("export albedo: E(theta_i) per order with errors, and E_avg") {
    const std::string input = gold_table();
    const fs::path dir = fresh_dir("export_albedo");
    export_to(input, "albedo", dir / "gold.csv");
    std::vector<std::string> comments;
    const auto rows = read_csv(dir / "gold.csv", &comments);
    REQUIRE(rows.size() == 1 + 18 * 3);
    CHECK(rows[0] == std::vector<std::string>{"case", "theta_i_deg", "phi_i_deg", "mu_i", "channel",
                                              "wavelength_nm", "l1", "l1_stderr", "l2plus",
                                              "l2plus_stderr", "linf", "linf_stderr"});
    const ResultCase c = read_result_case(input, "");
    const auto linf = c.read_albedo("linf_albedo"), l1 = c.read_albedo("l1_albedo"),
               e = c.read_albedo("linf_albedo_stderr");
    for (size_t r = 1; r < rows.size(); ++r) {
        CHECK(std::stod(rows[r][6]) == l1[r - 1]);
        CHECK(std::stod(rows[r][10]) == linf[r - 1]);
        CHECK(std::stod(rows[r][11]) == e[r - 1]);
    }
    // E_avg of channel 1 recomputed: 2 integral E mu dmu, trapezoid, E constant beyond the sweep.
    std::vector<std::pair<double, double>> mu_e{{1.0, linf[1]}};
    for (int t = 0; t < 18; ++t)
        mu_e.emplace_back(std::cos(radians(5.0 * t)), linf[size_t(t) * 3 + 1]);
    mu_e.emplace_back(0.0, linf[17 * 3 + 1]);
    std::sort(mu_e.begin(), mu_e.end());
    double avg = 0;
    for (size_t k = 1; k < mu_e.size(); ++k)
        avg += (mu_e[k].first - mu_e[k - 1].first) *
               (mu_e[k].first * mu_e[k].second + mu_e[k - 1].first * mu_e[k - 1].second);
    bool found = false;
    for (const std::string& line : comments)
        if (line.find("channel 1:") != std::string::npos) {
            const size_t at = line.find("linf ");
            CHECK(std::stod(line.substr(at + 5)) == doctest::Approx(avg).epsilon(1e-12));
            found = true;
        }
    CHECK(found);
}

TEST_CASE("export albedo --sweep: one table over a family of cases") {
    const std::string config = R"(seed = 5
[beam]
theta_i = [0, 30, 60, 85]
[sensor]
cells = 200
[surface]
size = 32
[trace]
rays = 16384
[[case]]
name = "a0.2"
ndf = { type = "ggx", alpha = 0.2 }
[[case]]
name = "a0.6"
ndf = { type = "ggx", alpha = 0.6 }
)";
    const std::string input = fixture("family", config);
    const fs::path dir = fresh_dir("export_albedo_sweep");
    export_to(input, "albedo", dir / "family.csv", "--sweep ndf.alpha");
    const auto rows = read_csv(dir / "family.csv", nullptr);
    REQUIRE(rows.size() == 1 + 2 * 4);
    CHECK(rows[0][0] == "ndf.alpha");
    CHECK(rows[1][0] == "0.2");
    CHECK(rows[5][0] == "0.6");
    CHECK(rows[5][1] == "a0.6");
    // Rougher mirrors scatter more light twice or more: L2+ grows with alpha.
    for (int k = 1; k <= 3; ++k) // theta_i 0, 30, 60 (on this 32^2 surface)
        CHECK(std::stod(rows[k + 4][9]) > 2 * std::stod(rows[k][9]));
}

TEST_CASE("export refuses what a format cannot hold, with a reason and nothing written") {
    const fs::path dir = fresh_dir("export_refusals");
    auto refused = [&](const std::string& input, const std::string& args, const std::string& why) {
        const Run r = run_gonio(dir, "export '" + input + "' " + args + " -o out.file");
        INFO(args << ": " << r.err);
        CHECK(r.code == 3);
        CHECK(r.err.find(why) != std::string::npos);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK_FALSE(fs::exists(dir / "out.file"));
        CHECK(files_in(dir) == 0); // no temporary file either
    };
    const std::string aniso =
        fixture("aniso", sweep_config("{ type = \"beckmann\", alpha_x = 0.2, alpha_y = 0.5 }",
                                      "{ type = \"mirror\" }", 800, 65536, 128, "[0, 90, 180, 270]",
                                      10, 80));
    refused(aniso, "--format merl", "isotropic BRDFs only");
    const std::string gold = gold_table();
    refused(gold, "--format rgl --orders t", "reflection only");
    refused(gold, "--format merl --orders t", "reflection only");
    const std::string sparse =
        fixture("sparse", sweep_config("{ type = \"beckmann\", alpha = 0.5 }",
                                       "{ type = \"mirror\" }", 200, 4096, 32, "0", 30, 60));
    refused(sparse, "--format rgl", "too sparse");
    refused(sparse, "--format merl", "too sparse");
    const std::string partial = fixture(
        "partial_turn", sweep_config("{ type = \"beckmann\", alpha_x = 0.2, alpha_y = 0.5 }",
                                     "{ type = \"mirror\" }", 200, 4096, 32, "[0, 45]", 10, 80));
    refused(partial, "--format rgl", "full turn");
    const std::string glass = fixture("glass", sweep_config("{ type = \"beckmann\", alpha = 0.3 }",
                                                            "{ type = \"dielectric\", eta = 1.5 }",
                                                            200, 16384, 32, "0", 45, 45));
    refused(glass, "--format rgl --orders t", "reflection only");
    refused(sparse, "--format astm --orders t", "transmits nothing");
    const std::string model_only =
        fixture("model_only",
                sweep_config("{ type = \"beckmann\", alpha = 0.5 }", "{ type = \"mirror\" }", 200,
                             4096, 32, "0", 5, 85),
                "model");
    for (const char* f : {"rgl", "merl", "astm", "albedo"})
        refused(model_only, std::string("--format ") + f, "models only");
    // A dielectric's transmission goes to ASTM as a BTDF.
    export_to(glass, "astm", dir / "glass.astm", "--orders t");
    CHECK(slurp(dir / "glass.astm").find("MEAS_NAME BTDF") != std::string::npos);
    fs::remove(dir / "glass.astm");
    // An unreadable input is an error (exit 1), not a refusal.
    const Run r = run_gonio(dir, "export missing.h5 --format astm -o out.file");
    CHECK(r.code == 1);
    CHECK(r.err.find("missing.h5") != std::string::npos);
}
