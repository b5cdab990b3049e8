// Measured height maps (heightfield/measured/): the readers on files gonio did not write (X3P from
// x3ptools, the ISO 25178-71 SDF example, spm-tools' GSF; tests/data/measured/README.md), damaged
// files refused, and the preparation steps checked on maps whose answer is known.
#include "core/config_error.h"
#include "heightfield/exr_io.h"
#include "heightfield/generate.h"
#include "heightfield/measured/gaussian_filter.h"
#include "heightfield/measured/map_preparation.h"
#include "heightfield/measured/measured_map.h"
#include "heightfield/measured/surface_character.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/surface_source.h"
#include "heightfield/surface_spec.h"

#include <cmath>
#include <cstring>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <zip.h>

using namespace gonio;
namespace fs = std::filesystem;

namespace {
std::string data(const std::string& name) {
    return std::string(GONIO_SOURCE_DIR) + "/tests/data/measured/" + name;
}

fs::path scratch() {
    const fs::path dir = fs::temp_directory_path() / ("gonio_measured_" + std::to_string(getpid()));
    fs::create_directories(dir);
    return dir;
}

void write_bytes(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

std::string bytes_of(const std::string& path) {
    return read_file_bytes(path);
}

// A copy of an X3P archive with one entry replaced.
void rezip(const std::string& from, const fs::path& to, const std::string& entry,
           const std::string& contents) {
    fs::copy_file(from, to, fs::copy_options::overwrite_existing);
    int error = 0;
    zip_t* z = zip_open(to.c_str(), 0, &error);
    REQUIRE(z);
    zip_source_t* s = zip_source_buffer(z, contents.data(), contents.size(), 0);
    REQUIRE(zip_file_add(z, entry.c_str(), s, ZIP_FL_OVERWRITE) >= 0);
    REQUIRE(zip_close(z) == 0);
}

std::string zip_entry(const std::string& path, const std::string& name) {
    int error = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_RDONLY, &error);
    REQUIRE(z);
    zip_stat_t st;
    REQUIRE(zip_stat(z, name.c_str(), 0, &st) == 0);
    std::string out(st.size, '\0');
    zip_file_t* f = zip_fopen(z, name.c_str(), 0);
    REQUIRE(zip_fread(f, out.data(), st.size) == zip_int64_t(st.size));
    zip_fclose(f);
    zip_discard(z);
    return out;
}

MeasuredMap plane_map(int nx, int ny, double a, double b, double c) {
    MeasuredMap m;
    m.nx = nx, m.ny = ny, m.dx = m.dy = 0.5, m.unit = kMeasuredUnit;
    m.z.resize(size_t(nx) * ny);
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) m.at(x, y) = a * x + b * y + c;
    return m;
}
} // namespace

TEST_CASE("X3P files of x3ptools read to the points, spacing and heights they state") {
    // csafe-logo.x3p: 741 x 419 points at 6.45e-07 m (x3ptools' README). Its md5checksum.hex no
    // longer matches main.xml, so it is refused unless the checksums are waived.
    CHECK_THROWS_WITH_AS(read_measured_map(data("csafe-logo.x3p")),
                         doctest::Contains("does not match its MD5 checksum"), std::runtime_error);
    const MeasuredMap logo = read_measured_map(data("csafe-logo.x3p"), {0, "um", false});
    CHECK(logo.format == "x3p");
    CHECK(logo.nx == 741);
    CHECK(logo.ny == 419);
    CHECK(logo.dx == doctest::Approx(0.645).epsilon(1e-9)); // micrometres
    CHECK(logo.dy == doctest::Approx(0.645).epsilon(1e-9));

    // pyramid.x3p: a 5 x 5 stepped pyramid of heights 2, 6, 10 (metres, increment 1 m).
    const MeasuredMap p = read_measured_map(data("pyramid.x3p"));
    REQUIRE(p.nx == 5);
    REQUIRE(p.ny == 5);
    CHECK(p.dx == 1e6);
    const double rings[5][5] = {
        {2, 2, 2, 2, 2}, {2, 6, 6, 6, 2}, {2, 6, 10, 6, 2}, {2, 6, 6, 6, 2}, {2, 2, 2, 2, 2}};
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 5; ++x) CHECK(p.at(x, y) == rings[y][x] * 1e6);

    // testing.x3p: 30 x 20 doubles at an increment of 0.0275 m; its heights are data.bin's.
    const MeasuredMap t = read_measured_map(data("testing.x3p"));
    CHECK(t.nx == 30);
    CHECK(t.ny == 20);
    CHECK(t.dx == doctest::Approx(27499.9996026357).epsilon(1e-12));
    const std::string bin = zip_entry(data("testing.x3p"), "bindata/data.bin");
    for (size_t k = 0; k < t.z.size(); k += 37) {
        double v;
        std::memcpy(&v, bin.data() + 8 * k, 8);
        CHECK(t.z[k] == v * 1e6);
    }
}

TEST_CASE("The ISO 25178-71 ASCII example reads to its points and scales") {
    const MeasuredMap m = read_measured_map(data("iso_25178_71_example.sdf"));
    CHECK(m.format == "sdf");
    REQUIRE(m.nx == 7);
    REQUIRE(m.ny == 4);
    CHECK(m.dx == doctest::Approx(1.0));
    CHECK(m.dy == doctest::Approx(1.0));
    // Values times Zscale 1e-6 m, in micrometres: the first profile and the last point.
    const double first[7] = {1.00000, 0.99874, 0.99495, 0.98865, 0.97986, 0.96858, 1.00000};
    for (int x = 0; x < 7; ++x) CHECK(m.at(x, 0) == doctest::Approx(first[x]).epsilon(1e-12));
    CHECK(m.at(6, 3) == doctest::Approx(0.97986).epsilon(1e-12));
}

TEST_CASE("The GSF of spm-tools reads to the points, size and float32 heights it states") {
    // spm-tools-test.gsf: 256 x 128 points, XReal 2e-05 m by YReal 1e-05 m, XYUnits and ZUnits
    // m (its header), heights the little-endian float32 after a 152-byte header and 4 NULs.
    const MeasuredMap m = read_measured_map(data("spm-tools-test.gsf"));
    CHECK(m.format == "gsf");
    REQUIRE(m.nx == 256);
    REQUIRE(m.ny == 128);
    CHECK(m.dx == doctest::Approx(0.078125).epsilon(1e-12)); // 20 um / 256, micrometres
    CHECK(m.dy == doctest::Approx(0.078125).epsilon(1e-12)); // 10 um / 128
    // Heights (micrometres) as numpy.frombuffer(..., '<f4') reads them, corners and an inside
    // point.
    CHECK(m.at(0, 0) == doctest::Approx(0.5758670909017383).epsilon(1e-12));
    CHECK(m.at(255, 0) == doctest::Approx(0.6401826340152184).epsilon(1e-12));
    CHECK(m.at(0, 127) == doctest::Approx(0.8215634466068877).epsilon(1e-12));
    CHECK(m.at(100, 50) == doctest::Approx(0.7178282999120711).epsilon(1e-12));
    CHECK(m.at(255, 127) == doctest::Approx(0.848683555432217).epsilon(1e-12));
    double lo = INFINITY, hi = -INFINITY;
    for (double z : m.z) lo = std::min(lo, z), hi = std::max(hi, z);
    CHECK(lo == doctest::Approx(0.5758670909017383).epsilon(1e-12));
    CHECK(hi == doctest::Approx(0.8533488085049612).epsilon(1e-12));
    CHECK(m.note == "GSF, XYUnits 'm', ZUnits 'm' read as micrometres");

    // Twice as wide as tall: the centred 128 x 128 square is kept, at the file's spacing.
    MapPreparation p;
    p.level = Levelling::none;
    p.spikes = 0;
    const PreparedMap square = prepare_measured_map(m, p, "spm-tools-test");
    REQUIRE(square.surface.n == 128);
    CHECK(square.missing_share == 0);
    for (int y = 0; y < 128; y += 31)
        for (int x = 0; x < 128; x += 29)
            CHECK(square.surface.at(x, y) == doctest::Approx(m.at(x + 64, y)).epsilon(1e-6));

    // Prepared as gonio surface does (plane levelled, spikes removed): its slopes' typical
    // 0.003-0.007 (median) are narrower than the metric resolves, though their heavy tail keeps
    // most facets out of its central cell. The GGX fit ends at the lowest alpha and says so;
    // Beckmann's, wider, does not.
    const SurfaceCharacter c = characterise_surface(prepare_measured_map(m, {}, "gsf").surface);
    CAPTURE(c.summary());
    REQUIRE(!c.unresolved);
    CHECK(c.ggx.at_lowest);
    CHECK(c.ggx.alpha_x == doctest::Approx(c.lowest_alpha).epsilon(1e-3));
    CHECK(!c.beckmann.at_lowest);
    CHECK(!c.beckmann.at_highest);
    CHECK(c.best().family == "beckmann");
    CHECK(c.summary().find("ggx: at the lowest alpha the metric resolves (0.0112)") !=
          std::string::npos);
    CHECK(c.summary().find("beckmann: at") == std::string::npos);
}

TEST_CASE("Damaged and truncated maps are refused with the file and the reason") {
    const fs::path dir = scratch();
    // A truncated X3P: not a zip any more.
    const std::string x3p = bytes_of(data("testing.x3p"));
    write_bytes(dir / "cut.x3p", x3p.substr(0, x3p.size() / 2));
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "cut.x3p").string()),
                         doctest::Contains("cut.x3p: not a readable X3P"), std::runtime_error);
    // Point data altered: its MD5 in main.xml fails; short point data is refused.
    std::string altered = zip_entry(data("testing.x3p"), "bindata/data.bin");
    altered[100] ^= 1;
    rezip(data("testing.x3p"), dir / "altered.x3p", "bindata/data.bin", altered);
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "altered.x3p").string()),
                         doctest::Contains("data.bin' does not match its MD5"), std::runtime_error);
    rezip(data("testing.x3p"), dir / "short.x3p", "bindata/data.bin", altered.substr(0, 800));
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "short.x3p").string(), {0, "um", false}),
                         doctest::Contains("holds 800 bytes"), std::runtime_error);
    // A truncated SDF, and one with a value that is not a number.
    std::string sdf = bytes_of(data("iso_25178_71_example.sdf"));
    write_bytes(dir / "cut.sdf", sdf.substr(0, sdf.find("0.97986 0.97862")));
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "cut.sdf").string()),
                         doctest::Contains("truncated"), std::runtime_error);
    std::string bad = sdf;
    bad.replace(bad.find("0.99874"), 7, "0.9x874");
    write_bytes(dir / "bad.sdf", bad);
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "bad.sdf").string()),
                         doctest::Contains("'0.9x874') is not a number"), std::runtime_error);
    // Not a height map at all.
    write_bytes(dir / "notes.bin", "hello");
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "notes.bin").string()),
                         doctest::Contains("not a height map gonio reads"), std::runtime_error);
    fs::remove_all(dir);
}

TEST_CASE("GSF and binary SDF files as their specifications lay them out, and plain matrices") {
    const fs::path dir = scratch();
    // GSF: header, NUL padding to a multiple of 4, float32 rows; XReal in metres.
    std::string gsf = "Gwyddion Simple Field 1.0\nXRes = 3\nYRes = 2\nXReal = 3e-06\n"
                      "YReal = 2e-06\nXYUnits = m\nZUnits = m\n";
    gsf.append(4 - gsf.size() % 4, '\0');
    const float values[6] = {1e-6f, 2e-6f, NAN, 4e-6f, 5e-6f, 6e-6f};
    gsf.append(reinterpret_cast<const char*>(values), sizeof values);
    write_bytes(dir / "map.gsf", gsf);
    const MeasuredMap g = read_measured_map((dir / "map.gsf").string());
    CHECK(g.format == "gsf");
    CHECK(g.nx == 3);
    CHECK(g.ny == 2);
    CHECK(g.dx == doctest::Approx(1.0));
    CHECK(g.at(1, 0) == doctest::Approx(2.0).epsilon(1e-6));
    CHECK(std::isnan(g.at(2, 0)));
    // A header asking for more points than gonio reads: refused before anything is allocated.
    write_bytes(dir / "huge.gsf",
                "Gwyddion Simple Field 1.0\nXRes = 30000\nYRes = 30000\n" + std::string(4, '\0'));
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "huge.gsf").string()),
                         doctest::Contains("at most 2^28"), std::runtime_error);
    write_bytes(dir / "cut.gsf", gsf.substr(0, gsf.size() - 4));
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "cut.gsf").string()),
                         doctest::Contains("truncated"), std::runtime_error);

    // Binary SDF: the 81-byte header of ISO 25178-71, then int16 points (-32768 missing).
    std::string sdf = "bISO-1.0" + std::string(34, ' ');
    auto put = [&](const void* p, size_t n) { sdf.append(static_cast<const char*>(p), n); };
    const std::uint16_t points = 2, profiles = 2;
    const double xs = 2e-6, ys = 2e-6, zs = 1e-9, zr = 1e-9;
    put(&points, 2), put(&profiles, 2), put(&xs, 8), put(&ys, 8), put(&zs, 8), put(&zr, 8);
    sdf += std::string{'\0', '\5', '\0'}; // no compression, int16, no checksum
    const std::int16_t raw[4] = {100, -32768, 300, 400};
    put(raw, sizeof raw);
    write_bytes(dir / "map.sdf", sdf);
    const MeasuredMap b = read_measured_map((dir / "map.sdf").string());
    CHECK(b.dx == doctest::Approx(2.0));
    CHECK(b.at(0, 0) == doctest::Approx(0.1)); // 100 x 1e-9 m
    CHECK(std::isnan(b.at(1, 0)));
    CHECK(b.at(1, 1) == doctest::Approx(0.4));

    // A plain CSV matrix: its spacing comes from the config, an empty field is missing.
    write_bytes(dir / "map.csv", "# heights, um\n1,2,3\n4,,6\n");
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "map.csv").string()),
                         doctest::Contains("surface.input_spacing"), std::runtime_error);
    const MeasuredMap c = read_measured_map((dir / "map.csv").string(), {0.25, "um", true});
    CHECK(c.format == "matrix");
    CHECK(c.nx == 3);
    CHECK(c.ny == 2);
    CHECK(c.dx == 0.25);
    CHECK(std::isnan(c.at(1, 1)));
    CHECK(c.at(2, 1) == 6);
    // In nanometres (surface.input_unit): spacing and heights converted to micrometres alike.
    const MeasuredMap n = read_measured_map((dir / "map.csv").string(), {250, "nm", true});
    CHECK(n.dx == doctest::Approx(0.25));
    CHECK(n.at(2, 1) == doctest::Approx(0.006));
    CHECK(n.note.find("in nm") != std::string::npos);
    CHECK(read_measured_map((dir / "map.csv").string(), {0.25, "µm", true}).at(2, 1) == 6);
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "map.csv").string(), {1, "inch", true}),
                         doctest::Contains("surface.input_unit 'inch' is not a length unit"),
                         std::runtime_error);
    write_bytes(dir / "ragged.txt", "1 2 3\n4 5\n");
    CHECK_THROWS_WITH_AS(read_measured_map((dir / "ragged.txt").string(), {1, "um", true}),
                         doctest::Contains("ragged.txt:2: 2 values; the rows above have 3"),
                         std::runtime_error);
    fs::remove_all(dir);
}

TEST_CASE("Preparation: levelling, filling, spikes and the square cut do what they say") {
    // A tilted plane with a hole and a spike: levelled to 0 everywhere, the hole filled (a
    // plane is harmonic, so its interpolation is exact), the spike found.
    MeasuredMap m = plane_map(40, 30, 0.3, -0.2, 5);
    for (int y = 10; y < 14; ++y)
        for (int x = 12; x < 18; ++x) m.at(x, y) = NAN;
    m.at(30, 20) += 50;
    MapPreparation p;
    p.level = Levelling::none;
    p.spikes = 20;
    p.max_missing = 0.05;
    const PreparedMap kept = prepare_measured_map(m, p, "plane");
    CHECK(kept.missing_share == doctest::Approx(24.0 / 1200));
    CHECK(kept.spike_share == doctest::Approx(1.0 / 1200));
    REQUIRE(kept.surface.n == 30); // the centred 30 x 30 square of 40 x 30
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 30; ++x)
            CHECK(kept.surface.at(x, y) ==
                  doctest::Approx(0.3 * (x + 5) - 0.2 * y + 5).epsilon(1e-6));
    p.level = Levelling::plane;
    const PreparedMap flat = prepare_measured_map(m, p, "plane");
    for (float h : flat.surface.h) CHECK(std::abs(h) < 1e-4);

    // Too many missing points: refused, naming the key.
    p.max_missing = 0.01;
    CHECK_THROWS_WITH_AS(prepare_measured_map(m, p, "plane"),
                         doctest::Contains("surface.max_missing allows 1 %"), std::runtime_error);
    // Cells that are not square: refused.
    MeasuredMap wide = plane_map(8, 8, 0, 0, 0);
    wide.dy = 0.6;
    p.max_missing = 0.05;
    CHECK_THROWS_WITH_AS(prepare_measured_map(wide, p, "wide"), doctest::Contains("not square"),
                         std::runtime_error);
}

TEST_CASE("The Gaussian high-pass transmits each wavelength as ISO 16610 states") {
    // Cosines of the mirror extension's basis are the filter's eigenfunctions: a wave of the
    // cut-off wavelength keeps exactly half its amplitude (the standard's definition), a short one
    // 1 - exp(-pi (alpha lc / lambda)^2), a constant nothing.
    const int nx = 96, ny = 64;
    const double dx = 0.5;
    const int kx = 6, ky = 40;          // half-periods across the map
    const double lx = 2 * nx * dx / kx; // 16
    const double ly = 2 * ny * dx / ky; // 1.6
    auto wave = [&](int x, int y, double a, double b) {
        return a * std::cos(M_PI * kx * (x + 0.5) / nx) + b * std::cos(M_PI * ky * (y + 0.5) / ny);
    };
    std::vector<double> z(size_t(nx) * ny);
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) z[size_t(y) * nx + x] = 7 + wave(x, y, 3, 0.2);
    CHECK(gaussian_transmission(1 / lx, lx) == doctest::Approx(0.5).epsilon(1e-12));
    gaussian_high_pass(z, nx, ny, dx, lx);
    const double keep_short = 1 - gaussian_transmission(1 / ly, lx);
    CHECK(keep_short > 0.99);
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x)
            REQUIRE(z[size_t(y) * nx + x] ==
                    doctest::Approx(wave(x, y, 1.5, 0.2 * keep_short)).epsilon(1e-9).scale(1));

    // Through the preparation: the form goes, the roughness stays, the step is reported; a
    // cut-off under two samples is refused naming the key.
    MeasuredMap m = plane_map(nx, ny, 0, 0, 0);
    m.dx = m.dy = dx;
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) m.at(x, y) = wave(x, y, 3, 0.2);
    MapPreparation p;
    p.level = Levelling::none, p.spikes = 0, p.high_pass = lx / 4;
    const PreparedMap filtered = prepare_measured_map(m, p, "waves");
    REQUIRE(filtered.report.size() == 2); // and the square cut
    CHECK(filtered.report[0].find("high-pass: Gaussian, cut-off 4") == 0);
    const double long_kept = 1 - gaussian_transmission(1 / lx, lx / 4);
    CHECK(long_kept < 0.05); // a Gaussian rolls off slowly: 4 % at four times the cut-off
    const int x0 = (nx - ny) / 2;
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < ny; ++x)
            REQUIRE(filtered.surface.at(x, y) ==
                    doctest::Approx(wave(x0 + x, y, 3 * long_kept,
                                         0.2 * (1 - gaussian_transmission(1 / ly, lx / 4))))
                        .scale(1)
                        .epsilon(1e-5)); // float heights
    p.high_pass = 0.9;
    CHECK_THROWS_WITH_AS(prepare_measured_map(m, p, "waves"),
                         doctest::Contains("waves: key 'surface.high_pass': 0.9 is under two"),
                         ConfigError);
}

TEST_CASE("gonio's own OpenEXR maps are read exactly as before unless a key asks") {
    const fs::path dir = scratch();
    HeightField s(16, 0.5);
    for (int k = 0; k < 256; ++k) s.h[k] = float(std::sin(0.37 * k) + 0.01 * k);
    ExrAttributes a;
    a.text["gonio_ndf"] = "test";
    a.numbers["gonio_spacing"] = 0.5;
    write_height_exr((dir / "own.exr").string(), s, a);
    SurfaceSpec spec;
    spec.input = (dir / "own.exr").string();
    std::vector<std::string> report;
    const HeightField same = read_input_map(spec, report);
    CHECK(same.h == read_height_exr(spec.input).h);
    CHECK(same.spacing == 0.5);
    CHECK(report.empty());
    spec.prepare_asked = true, spec.level = "plane";
    const HeightField levelled = read_input_map(spec, report);
    CHECK(levelled.h != same.h);
    CHECK(report.size() >= 2);
    spec.level = "none", report.clear();
    spec.high_pass = 2;
    const HeightField filtered = read_input_map(spec, report);
    CHECK(filtered.h != same.h);
    CHECK(report.back().find("high-pass") == 0);
    fs::remove_all(dir);
}

TEST_CASE("A generated surface's closest analytic distribution is its own family and roughness") {
    SurfaceSpec spec;
    spec.size = 128;
    spec.seed = 9;
    const Ggx ggx(0.3);
    const Beckmann beckmann(0.4);
    const SurfaceCharacter g = characterise_surface(generate_surface(ggx, spec, 2));
    CHECK(g.best().family == "ggx");
    CHECK(g.ggx.alpha_x == doctest::Approx(0.3).epsilon(0.05));
    const SurfaceCharacter b = characterise_surface(generate_surface(beckmann, spec, 2));
    CHECK(b.best().family == "beckmann");
    CHECK(b.beckmann.alpha_x == doctest::Approx(0.4).epsilon(0.05));
    // Isotropic: the principal RMS slopes agree to a few per cent.
    CHECK(b.alpha_major / b.alpha_minor < 1.1);
}

TEST_CASE("An anisotropic surface's closest distribution along x and y is its own") {
    SurfaceSpec spec;
    spec.size = 128;
    spec.seed = 11;
    const Ggx ggx(0.15, 0.45);
    const SurfaceCharacter g = characterise_surface(generate_surface(ggx, spec, 2));
    CHECK(g.best_xy().family == "ggx");
    CHECK(g.ggx_xy.alpha_x == doctest::Approx(0.15).epsilon(0.05));
    CHECK(g.ggx_xy.alpha_y == doctest::Approx(0.45).epsilon(0.05));
    CHECK(g.ggx_xy.distance < 0.5 * g.ggx.distance); // the isotropic fit cannot follow it
    CHECK(g.major_axis_deg == doctest::Approx(90).epsilon(0.02));
    CHECK(g.best_xy().ndf_toml().find("{ type = \"ggx\", alpha_x = 0.1") == 0);
}

TEST_CASE("A surface smoother than the metric resolves has no fit, and a flat one no correlation") {
    // Heights of RMS slope ~0.003: every facet in the metric's central cell, where GGX and
    // Beckmann narrower than 0.011 cannot be integrated: no fit, said so.
    HeightField s(64, 1.0);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            s.h[size_t(y) * 64 + x] = float(0.01 * std::sin(0.7 * x) * std::cos(0.3 * y));
    const SurfaceCharacter c = characterise_surface(s);
    CHECK(c.unresolved);
    CHECK(c.lowest_alpha == doctest::Approx(0.0112).epsilon(0.01));
    CHECK(c.lines().back().find("closest analytic NDFs: none") == 0);
    CHECK(c.summary().find("nan") == std::string::npos);

    // A fit at an end of the search says so: an alternating 0, 60 ridge (slopes +-60, beyond
    // any GGX or Beckmann alpha searched) ends at the highest alpha.
    HeightField steep(32, 1.0);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) steep.h[size_t(y) * 32 + x] = float(60 * ((x + y) % 2));
    const SurfaceCharacter st = characterise_surface(steep);
    CAPTURE(st.summary());
    CHECK(st.ggx.at_highest);
    CHECK(st.summary().find("ggx: at the highest alpha searched (20)") != std::string::npos);

    const SurfaceCharacter flat = characterise_surface(HeightField(32, 1.0));
    CHECK(flat.unresolved);
    CHECK(flat.correlation_x == 0);
    CHECK(flat.summary().find("inf") == std::string::npos);
    CHECK(flat.alpha_major == 0);
}
