// The pieces under the exporters: the RGL readers' 2-D warp (sample and invert are inverses, the
// samples follow the density), the tensor container, and the colour conversion.
#include "core/chi_square.h"
#include "core/colour.h"
#include "core/random.h"
#include "gonio/export/piecewise_linear_2d.h"
#include "gonio/export/tensor_file.h"
#include "gonio/material/ior_table.h"
#include "tests/rgl_reader.h"

#include <cstdio>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>

using namespace gonio;

namespace {
PiecewiseLinear2D bumpy(bool normalize) {
    std::vector<double> d;
    const int w = 9, h = 7;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            d.push_back(x == 0 ? 0.0
                               : 0.2 + std::sin(0.7 * x * y) * std::sin(0.7 * x * y) +
                                     (y == 3 ? 2 : 0));
    return PiecewiseLinear2D(d, w, h, normalize);
}
} // namespace

TEST_CASE("piecewise-linear 2-D warp: invert undoes sample, and the pdf is the density") {
    const PiecewiseLinear2D warp = bumpy(true);
    Rng rng{31, 1};
    for (int k = 0; k < 20000; ++k) {
        const PiecewiseLinear2D::Point u{rng.uniform(), rng.uniform()};
        double pdf = 0, pdf2 = 0;
        const auto p = warp.sample(u, &pdf);
        const auto back = warp.invert(p, &pdf2);
        REQUIRE(back[0] == doctest::Approx(u[0]).epsilon(1e-9));
        REQUIRE(back[1] == doctest::Approx(u[1]).epsilon(1e-9));
        REQUIRE(pdf == doctest::Approx(warp.eval(p)).epsilon(1e-9));
        REQUIRE(pdf2 == doctest::Approx(pdf).epsilon(1e-9));
    }
    // At u = 0 on a density that starts at 0 (the RGL vndf's first column): no NaN.
    const auto p = warp.sample({0.0, 0.5});
    CHECK(p[0] == 0.0);
    CHECK(std::isfinite(p[1]));
}

TEST_CASE("piecewise-linear 2-D warp: samples follow the density (chi-square)") {
    const PiecewiseLinear2D warp = bumpy(true);
    const int bins = 24, n = 400000;
    std::vector<double> observed(bins * bins, 0.0), expected(bins * bins, 0.0);
    Rng rng{32, 1};
    for (int k = 0; k < n; ++k) {
        const auto p = warp.sample({rng.uniform(), rng.uniform()});
        const int bx = std::min(int(p[0] * bins), bins - 1),
                  by = std::min(int(p[1] * bins), bins - 1);
        observed[by * bins + bx] += 1;
    }
    const int sub = 16; // midpoint rule inside each bin (the density is bilinear on its patches)
    for (int by = 0; by < bins; ++by)
        for (int bx = 0; bx < bins; ++bx) {
            double m = 0;
            for (int i = 0; i < sub; ++i)
                for (int j = 0; j < sub; ++j)
                    m += warp.eval({(bx + (i + 0.5) / sub) / bins, (by + (j + 0.5) / sub) / bins});
            expected[by * bins + bx] = n * m / (double(sub) * sub * bins * bins);
        }
    const ChiSquareResult r = chi_square_test(observed, expected);
    CHECK(r.failure == "");
    CHECK(r.p_value > 0.01);
    // Unnormalised, eval is the raw interpolant: its vertices are the data.
    const PiecewiseLinear2D raw = bumpy(false);
    CHECK(raw.eval({1.0 / 8, 3.0 / 6}) ==
          doctest::Approx(0.2 + std::pow(std::sin(0.7 * 3), 2) + 2));
}

TEST_CASE("tensor file: the container reads back field by field") {
    const auto path = std::filesystem::temp_directory_path() / "gonio_tensor_test.bsdf";
    {
        TensorFileWriter w;
        w.add_u8("description", {3}, {'a', 'b', 'c'});
        w.add_f32("theta_i", {2}, {0.0, 0.5});
        w.add_f32("grid", {2, 3}, {1, 2, 3, 4, 5, 6});
        std::ofstream out(path, std::ios::binary);
        w.write(out);
    }
    const auto fields = test::read_tensor_file(path.string());
    CHECK(fields.at("description").text() == "abc");
    CHECK(fields.at("theta_i").values == std::vector<double>{0.0, 0.5});
    CHECK(fields.at("grid").shape == std::vector<std::uint64_t>{2, 3});
    CHECK(fields.at("grid").values == std::vector<double>{1, 2, 3, 4, 5, 6});
    std::filesystem::remove(path);
}

TEST_CASE("colour: D65 white, a white reflector in sRGB, and monochromatic lines") {
    const ColourTables t = load_colour_tables(data_directory());
    REQUIRE(t.wavelength_nm.size() == 81);
    // The D65 white point from the tables: x = 0.3127, y = 0.3290 (CIE 15:2004).
    const Matrix3xN xyz = spectrum_to_xyz_matrix(t, {380, 780});
    const double one[2] = {1, 1};
    const auto w = map_channels(xyz, one);
    CHECK(w[1] == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(w[0] / (w[0] + w[1] + w[2]) == doctest::Approx(0.3127).epsilon(2e-4));
    CHECK(w[1] / (w[0] + w[1] + w[2]) == doctest::Approx(0.3290).epsilon(2e-4));
    const auto rgb = map_channels(spectrum_to_linear_srgb_matrix(t, {450, 550, 650}),
                                  std::vector<double>{1, 1, 1}.data());
    for (double c : rgb) CHECK(c == doctest::Approx(1.0).epsilon(2e-3));
    // A spectrum rising to the red is reddish; a constant 0.5 is grey 0.5.
    const auto red = map_channels(spectrum_to_linear_srgb_matrix(t, {450, 550, 650}),
                                  std::vector<double>{0.1, 0.3, 0.9}.data());
    CHECK(red[0] > red[1]);
    CHECK(red[1] > red[2]);
}

TEST_CASE("CIEDE2000: the 34 test pairs of Sharma, Wu and Dalal (2005) to 1e-4") {
    std::ifstream in(std::string(GONIO_SOURCE_DIR) + "/tests/data/ciede2000_sharma2005.csv");
    std::string line;
    int pairs = 0;
    bool header = true;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (header) {
            header = false;
            continue;
        }
        std::array<double, 7> v{};
        std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4],
                    &v[5], &v[6]);
        const std::array<double, 3> a{v[0], v[1], v[2]}, b{v[3], v[4], v[5]};
        INFO("pair " << pairs + 1);
        CHECK(std::abs(ciede2000(a, b) - v[6]) <= 1e-4);
        CHECK(std::abs(ciede2000(b, a) - v[6]) <= 1e-4); // symmetric
        ++pairs;
    }
    CHECK(pairs == 34);
    CHECK(ciede2000({52, 10, -30}, {52, 10, -30}) == 0);
    // sRGB white is L* = 100, a* = b* = 0.
    const auto white = xyz_to_lab(linear_srgb_to_xyz({1, 1, 1}));
    CHECK(white[0] == doctest::Approx(100).epsilon(1e-3));
    CHECK(std::abs(white[1]) < 0.05);
    CHECK(std::abs(white[2]) < 0.05);
}
