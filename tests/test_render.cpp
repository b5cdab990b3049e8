// gonio render: a white furnace, a Lambertian table against the analytic Lambertian, convergence
// as 1/sqrt(spp), thread-count independence, the image files, and the command's bad arguments.
#include "core/chi_square.h"
#include "core/random.h"
#include "core/threads.h"
#include "gonio/render/colour_difference.h"
#include "gonio/render/renderer.h"
#include "tests/cli_harness.h"
#include "tests/export_fixtures.h"

#include <cmath>
#include <doctest/doctest.h>
#include <png.h>

using namespace gonio;
using namespace gonio::test;

namespace {
// A glossy lobe around the mirror direction, every incidence's cells scaled so that its albedo
// (sum f_c Omega_perp_c) is exactly `albedo`.
std::shared_ptr<const BsdfTable> glossy_table(double albedo, bool constant = false) {
    TableData d;
    d.theta_i_deg = {0, 20, 40, 60, 80};
    d.phi_i_deg = {0};
    d.cells = 800;
    d.channels = 3;
    const BeckersSensor sensor(d.cells);
    for (double t : d.theta_i_deg) {
        const Vec3 wi = spherical_direction(radians(t), 0);
        const Vec3 r{-wi.x, -wi.y, wi.z};
        std::vector<double> f;
        double sum = 0;
        for (const SensorCell& c : sensor.cells()) {
            const double v = constant ? 1.0 : 0.2 + 3 * std::exp(10 * (dot(r, c.center) - 1));
            f.push_back(v);
            sum += v * c.projected_solid_angle;
        }
        for (double v : f)
            for (int ch = 0; ch < 3; ++ch) d.f.push_back(v * albedo / sum);
    }
    return std::make_shared<const BsdfTable>(d);
}

struct Stats {
    double mean = 0, sd = 0;
    long n = 0;
};
Stats object_stats(const RenderResult& r, int channel = 1) {
    Stats s;
    double sum = 0, sum2 = 0;
    for (size_t k = 0; k < r.object.size(); ++k)
        if (r.object[k]) {
            const double v = r.image.rgb[k * 3 + channel];
            sum += v, sum2 += v * v, ++s.n;
        }
    s.mean = sum / double(s.n);
    s.sd = std::sqrt(std::max(0.0, sum2 / double(s.n) - s.mean * s.mean));
    return s;
}
double mean_square_difference(const Image& a, const Image& b,
                              const std::vector<std::uint8_t>& mask) {
    double sum = 0;
    long n = 0;
    for (size_t k = 0; k < mask.size(); ++k)
        if (mask[k]) {
            const double d = double(a.rgb[k * 3 + 1]) - double(b.rgb[k * 3 + 1]);
            sum += d * d, ++n;
        }
    return sum / double(n);
}
} // namespace

TEST_CASE("render: a white furnace (albedo-1 BSDFs under a uniform environment) renders 1") {
    const RenderScene scene(RenderObject::torus); // concave: it sees itself
    const Environment env = Environment::uniform(1.0);
    const TableBsdf object(glossy_table(1.0));
    const LambertianBsdf floor({1, 1, 1});
    RenderSettings s;
    s.width = 64, s.height = 48, s.spp = 64, s.max_depth = 64;
    const RenderResult r = render(scene, env, object, floor, s);
    const Stats st = object_stats(r);
    MESSAGE("object pixels " << st.n << ": mean " << st.mean << ", sd " << st.sd);
    REQUIRE(st.n > 300);
    // Every pixel's expectation is 1: the mean over pixels is 1 within its standard error.
    CHECK(std::abs(st.mean - 1) < 4 * st.sd / std::sqrt(double(st.n)));
    CHECK(st.sd < 0.05);
}

TEST_CASE("render: a Lambertian table renders like the analytic Lambertian object") {
    const RenderScene scene(RenderObject::sphere);
    const Environment env = Environment::overcast_sky();
    const TableBsdf table(glossy_table(0.7, true));
    const LambertianBsdf analytic({0.7, 0.7, 0.7}), floor({0.5, 0.5, 0.5});
    RenderSettings s;
    s.width = 64, s.height = 48, s.spp = 32, s.light = true;
    s.light_direction = spherical_direction(radians(40), radians(150));
    auto with = [&](const SurfaceBsdf& b, std::uint64_t seed) {
        RenderSettings t = s;
        t.seed = seed;
        return render(scene, env, b, floor, t);
    };
    const RenderResult t1 = with(table, 1), t2 = with(table, 2), a1 = with(analytic, 1),
                       a2 = with(analytic, 2);
    // Noise of each from two seeds; the table against the analytic object must differ by noise
    // alone: E[(t - a)^2] = var_t + var_a.
    const double var_t = 0.5 * mean_square_difference(t1.image, t2.image, t1.object);
    const double var_a = 0.5 * mean_square_difference(a1.image, a2.image, t1.object);
    // (Independent seeds: the same seed would share camera rays and environment samples.)
    const double cross = mean_square_difference(t1.image, a2.image, t1.object);
    MESSAGE("variances: table " << var_t << ", analytic " << var_a << "; difference " << cross);
    CHECK(cross == doctest::Approx(var_t + var_a).epsilon(0.15));
    const Stats st = object_stats(t1), sa = object_stats(a1);
    CHECK(std::abs(st.mean - sa.mean) < 4 * std::sqrt((var_t + var_a) / double(st.n)));
}

TEST_CASE("render: the error falls as 1 / sqrt(spp)") {
    const RenderScene scene(RenderObject::torus);
    const Environment env = Environment::overcast_sky();
    const TableBsdf object(glossy_table(0.8));
    const LambertianBsdf floor({0.5, 0.5, 0.5});
    RenderSettings s;
    s.width = 40, s.height = 30;
    s.spp = 4096;
    s.seed = 99;
    const RenderResult reference = render(scene, env, object, floor, s);
    std::vector<double> rmse;
    for (int spp : {4, 16, 64}) {
        s.spp = spp;
        s.seed = 7;
        const RenderResult r = render(scene, env, object, floor, s);
        std::vector<std::uint8_t> all(r.object.size(), 1);
        rmse.push_back(std::sqrt(mean_square_difference(r.image, reference.image, all)));
    }
    const double slope1 = std::log(rmse[1] / rmse[0]) / std::log(4.0);
    const double slope2 = std::log(rmse[2] / rmse[1]) / std::log(4.0);
    MESSAGE("rmse " << rmse[0] << ", " << rmse[1] << ", " << rmse[2] << ": slopes " << slope1
                    << ", " << slope2);
    CHECK(slope1 == doctest::Approx(-0.5).epsilon(0.2));
    CHECK(slope2 == doctest::Approx(-0.5).epsilon(0.2));
}

TEST_CASE("render: the same image for 1 and 2 threads") {
    const RenderScene scene(RenderObject::sphere);
    const Environment env = Environment::overcast_sky();
    const TableBsdf object(glossy_table(0.8));
    const LambertianBsdf floor({0.5, 0.5, 0.5});
    RenderSettings s;
    s.width = 32, s.height = 24, s.spp = 8;
    Image one, two;
    {
        const auto limit = limit_threads(1);
        one = render(scene, env, object, floor, s).image;
    }
    {
        const auto limit = limit_threads(2);
        two = render(scene, env, object, floor, s).image;
    }
    CHECK(one.rgb == two.rgb);
}

TEST_CASE("render: PNG and EXR files are written whole under their names") {
    const fs::path dir = fresh_dir("render_files");
    Image img(5, 4);
    for (size_t k = 0; k < img.rgb.size(); ++k) img.rgb[k] = float(k) / float(img.rgb.size());
    write_png(img, (dir / "a.png").string());
    write_exr(img, (dir / "a.exr").string());
    CHECK(files_in(dir) == 2); // no temporary left
    const Image back = read_exr_rgb((dir / "a.exr").string());
    CHECK(back.width == 5);
    CHECK(back.rgb == img.rgb);
    FILE* f = std::fopen((dir / "a.png").c_str(), "rb");
    REQUIRE(f);
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_read_info(png, info);
    CHECK(png_get_image_width(png, info) == 5);
    CHECK(png_get_image_height(png, info) == 4);
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    CHECK_THROWS_WITH(write_png(img, (dir / "no_such_dir" / "b.png").string()),
                      doctest::Contains("b.png"));
    CHECK(files_in(dir) == 2);
    // The false-colour scale: blue at 0, red at the top of the scale and beyond.
    CHECK(false_colour_of(0)[2] > 0.5f);
    CHECK(false_colour_of(kDeltaEScale)[0] > 0.8f);
    CHECK(false_colour_of(3 * kDeltaEScale) == false_colour_of(kDeltaEScale));
}

TEST_CASE("gonio render: images, the Delta E00 comparison, and bad arguments") {
    const std::string input = gold_table();
    const fs::path dir = fresh_dir("render_cli");
    Run r = run_gonio(dir, "render '" + input +
                               "' -o out.png --compare l1 --size 48x36 --spp 4 --quiet");
    INFO(r.err);
    REQUIRE(r.code == 0);
    for (const char* f : {"out.png", "out.exr", "out_l1.png", "out_l1.exr", "out_de00.png"})
        CHECK(fs::exists(dir / f));
    CHECK(r.out.find("Delta E00") != std::string::npos);
    r = run_gonio(dir, "render '" + input +
                           "' -o model.png --compare model --size 48x36 --spp 4 --quiet");
    CHECK(r.code == 0);
    CHECK(fs::exists(dir / "model_model.png"));
    const int before = files_in(dir);
    auto bad = [&](const std::string& args, int code, const std::string& why) {
        const Run b = run_gonio(dir, "render '" + input + "' " + args);
        INFO(args << ": " << b.err);
        CHECK(b.code == code);
        CHECK(b.err.find(why) != std::string::npos);
        CHECK(files_in(dir) == before);
    };
    bad("-o x.png --size 0x10", 2, "--size");
    bad("-o x.png --size 40", 2, "WxH");
    bad("-o x.png --light 95,0", 2, "theta in [0, 90)");
    bad("-o x.jpg", 2, ".png");
    bad("-o out.png", 2, "--overwrite");
    bad("-o x.png --env missing.exr", 1, "missing.exr");
    bad("-o x.png --object teapot", 2, "teapot");
    bad("-o x.png --compare both", 2, "both");
}

TEST_CASE("render: the environment sampler follows its pdf (chi-square), and an EXR map loads") {
    // A sky with a bright patch: samples binned on a 16 x 8 lat-long grid against the pdf's mass.
    Image m(64, 32);
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x)
            for (int c = 0; c < 3; ++c)
                m.at(x, y)[c] = float(0.2 + (x > 40 && x < 46 && y > 8 && y < 12 ? 30.0 : 0.0) +
                                      0.1 * std::sin(0.3 * x));
    const Environment env(m);
    const int nu = 16, nv = 8, n = 400000;
    std::vector<double> observed(nu * nv, 0.0), expected(nu * nv, 0.0);
    Rng rng{41, 1};
    for (int k = 0; k < n; ++k) {
        double pdf = 0;
        const Vec3 d = env.sample(rng.uniform(), rng.uniform(), pdf);
        REQUIRE(pdf == doctest::Approx(env.pdf(d)).epsilon(1e-9));
        const int u = std::min(nu - 1, int(spherical_phi(d) / kTwoPi * nu));
        const int v = std::min(nv - 1, int(spherical_theta(d) / kPi * nv));
        observed[v * nu + u] += 1;
    }
    // Expected: the pdf integrated over each bin (midpoint rule on a grid finer than the texels).
    const int sub = 32;
    double total = 0;
    for (int v = 0; v < nv; ++v)
        for (int u = 0; u < nu; ++u) {
            double mass = 0;
            for (int i = 0; i < sub; ++i)
                for (int j = 0; j < sub; ++j) {
                    const double phi = kTwoPi * (u + (i + 0.5) / sub) / nu;
                    const double z0 = std::cos(kPi * (v + double(j) / sub) / nv);
                    const double z1 = std::cos(kPi * (v + (j + 1.0) / sub) / nv);
                    const double z = 0.5 * (z0 + z1), r = std::sqrt(1 - z * z);
                    mass += env.pdf({r * std::cos(phi), r * std::sin(phi), z}) * (z0 - z1) *
                            (kTwoPi / (nu * sub));
                }
            expected[v * nu + u] = n * mass;
            total += mass;
        }
    CHECK(total == doctest::Approx(1.0).epsilon(1e-3));
    const ChiSquareResult r = chi_square_test(observed, expected);
    CHECK(r.failure == "");
    CHECK(r.p_value > 0.01);
    // The same map through an EXR file.
    const fs::path dir = fresh_dir("render_env");
    write_exr(m, (dir / "env.exr").string());
    const Environment loaded = Environment::from_exr((dir / "env.exr").string());
    const Vec3 d = spherical_direction(1.0, 2.0);
    CHECK(loaded.radiance(d)[0] == doctest::Approx(env.radiance(d)[0]));
}
