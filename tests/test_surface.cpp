#include "core/random.h"
#include "core/special_functions.h"
#include "heightfield/exr_io.h"
#include "heightfield/frankot_chellappa.h"
#include "heightfield/generate.h"
#include "heightfield/ndf/anisotropic_blend.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/generalized_normal.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/ndf/mixture_ndf.h"
#include "heightfield/ndf/sinc_ndf.h"
#include "heightfield/ndf/student_t.h"
#include "heightfield/slope_marginal.h"
#include "heightfield/surface_generator.h"
#include "heightfield/surface_metrics.h"
#include "heightfield/surface_source.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <memory>
#include <tbb/global_control.h>
#include <unistd.h>

using namespace gonio;
namespace fs = std::filesystem;

namespace {
// The total-variation distance between D cos and an ideal sample of `facets` independent normals
// drawn from it, on the same cells, is the reference for fidelity bars. Per cell, N_c/n - p_c is
// about normal with variance v_c = p_c (1 - p_c) / n, so E|.| = sqrt(2 v_c / pi) and
// Var|.| = (1 - 2/pi) v_c; the TV (half the sum) has mean m and standard deviation s below.
struct IidDistance {
    double mean = 0, sigma = 0;
};
IidDistance iid_distance(const std::vector<double>& target_mass, double facets) {
    IidDistance d;
    double var = 0;
    for (double p : target_mass) {
        const double v = p * (1 - p) / facets;
        d.mean += 0.5 * std::sqrt(2 * v / kPi);
        var += 0.25 * (1 - 2 / kPi) * v;
    }
    d.sigma = std::sqrt(var);
    return d;
}

// iterations 0: the generator's default (sliced matching 100, Algorithm 1 R19's 500).
HeightField make(const Ndf& ndf, const std::string& generator, int iterations = 0,
                 std::uint64_t seed = 1, const std::string& constraint = "none",
                 GenerationLog* log = nullptr) {
    SurfaceSpec s;
    s.size = 256;
    if (iterations > 0)
        s.iterations = iterations;
    else if (generator == "algorithm1")
        s.iterations = 500;
    s.generator = &generator_named(generator);
    s.constraint = constraint == "none"    ? Constraint::none
                   : constraint == "domes" ? Constraint::domes
                                           : Constraint::holes;
    s.seed = seed;
    return generate_surface(ndf, s, 2, log);
}

// bar: "iid" = no further from D cos than an ideal independent sample of as many facets (its
// mean TV plus 3 standard deviations); otherwise a multiple of the ideal sample's mean TV.
void check_fidelity(const HeightField& h, const Ndf& ndf, double ax, double ay, double bar_factor) {
    const SurfaceMetrics m = measure_surface(h, ndf, 1000);
    const IidDistance iid = iid_distance(m.target_mass, 2.0 * h.n * h.n);
    const double bar = bar_factor == 0 ? iid.mean + 3 * iid.sigma : bar_factor * iid.mean;
    CAPTURE(ndf.describe());
    CAPTURE(m.ndf_distance);
    CAPTURE(iid.mean);
    CAPTURE(bar);
    CAPTURE(m.alpha_eff_x);
    CAPTURE(m.alpha_eff_y);
    CHECK(m.ndf_distance <= bar);
    CHECK(std::abs(m.alpha_eff_x / ax - 1) < 0.03);
    CHECK(std::abs(m.alpha_eff_y / ay - 1) < 0.03);
}
} // namespace

TEST_CASE("Frankot-Chellappa recovers a periodic surface from its exact gradients") {
    for (int n : {16, 64, 257}) {
        // White-noise heights: every frequency up to Nyquist, where central differences fail.
        std::vector<float> h(size_t(n) * n), p(h.size()), q(h.size()), out;
        Rng rng{11, std::uint64_t(n)};
        double mean = 0;
        for (float& v : h) mean += (v = float(rng.uniform() - 0.5));
        mean /= double(h.size());
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const size_t k = size_t(y) * n + x;
                p[k] = h[size_t(y) * n + (x + 1) % n] - h[k];
                q[k] = h[size_t((y + 1) % n) * n + x] - h[k];
            }
        FrankotChellappa fc(n, 2);
        fc.integrate(p, q, out);
        double worst = 0;
        for (size_t k = 0; k < h.size(); ++k)
            worst = std::max(worst, std::abs(out[k] - (h[k] - mean)));
        CAPTURE(n);
        CHECK(worst < 2e-5); // float round-off of the transforms
    }
}

TEST_CASE("the exact slope marginal: Beckmann and GGX quantiles against their closed forms") {
    // Stretched unit-roughness slopes: Beckmann's marginal is a normal of variance 1/2
    // (erf_quantile), GGX's has the CDF (1 + x / sqrt(1 + x^2)) / 2. Whatever alpha_x, alpha_y.
    const TargetQuantiles beckmann(Beckmann(0.75), 1 << 20), ggx(Ggx(0.3, 0.6), 1 << 20);
    auto ggx_quantile = [](double u) {
        const double v = 2 * u - 1;
        return v / std::sqrt(1 - v * v);
    };
    for (int i = 1; i < 2000; ++i) {
        const double u = 0.002 + 0.996 * i / 2000.0; // the table
        CAPTURE(u);
        CHECK(std::abs(beckmann(u) - erf_quantile(u)) <= 1e-6 * (1 + std::abs(erf_quantile(u))));
        CHECK(std::abs(ggx(u) - ggx_quantile(u)) <= 1e-5 * (1 + std::abs(ggx_quantile(u))));
    }
    for (double tail : {1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6}) // integrated and inverted
        for (double u : {tail, 1 - tail}) {
            CAPTURE(u);
            CHECK(beckmann(u) == doctest::Approx(erf_quantile(u)).epsilon(1e-4));
            CHECK(ggx(u) == doctest::Approx(ggx_quantile(u)).epsilon(1e-4));
        }
    // Ranks beyond the extreme order statistics of 2^20 projections are clamped to them.
    CHECK(beckmann(0.0) == doctest::Approx(erf_quantile(0.5 / (1 << 20))).epsilon(1e-4));
    CHECK(ggx(1.0) == doctest::Approx(ggx_quantile(1 - 0.5 / (1 << 20))).epsilon(1e-4));
}

TEST_CASE("sliced matching: Beckmann 0.5 and GGX 0.3 at 256^2 follow their NDF") {
    // Bar: no further from D cos than an ideal independent sample of as many facets, and the
    // effective alpha within 3 %.
    const Beckmann beckmann(0.5);
    check_fidelity(make(beckmann, "sliced-matching"), beckmann, 0.5, 0.5, 0);
    const Ggx ggx(0.3);
    check_fidelity(make(ggx, "sliced-matching"), ggx, 0.3, 0.3, 0);
}

TEST_CASE("sliced matching: heavy-tailed Student's t and peaked generalised normal") {
    // The generalised family is shape-invariant: sliced matching applies as for Beckmann.
    const StudentT heavy(0.5, 0.5, 2.2);
    check_fidelity(make(heavy, "sliced-matching"), heavy, 0.5, 0.5, 0);
    const GeneralizedNormal peaked(0.4, 0.4, 1.0);
    check_fidelity(make(peaked, "sliced-matching"), peaked, 0.4, 0.4, 0);
}

TEST_CASE("sliced matching: a multi-lobe sinc curve and two anisotropic blends [R19 Eq. 10]") {
    // The sinc curve is shape-invariant (alpha = 1); the blends are not, so their target is
    // projected and sorted along each direction. alpha_eff is then the median-slope ratio to D.
    // Bar: 2.5 x the ideal sample's mean TV. These slope distributions are not elliptical (rings
    // of lobes; a blend's cos^2 phi mix), and integration pulls the gradient field towards an
    // elliptical one: the TV stays at 1.5-1.9 x the ideal from 100 to 2000 iterations and at
    // 100 bins does not fall with the size (0.024 for the sinc, 0.035 for the GGX/Beckmann blend
    // at 256^2 and 512^2), while an elliptical target through the same per-direction path (a
    // one-component mixture of anisotropic Beckmann) reaches the ideal. Recorded in
    // docs/microsurfaces.md.
    const SincNdf sinc(6.0, 0.05, 128);
    check_fidelity(make(sinc, "sliced-matching"), sinc, 1, 1, 2.5);
    const AnisotropicBlend ggx_beckmann(std::make_unique<Ggx>(0.5, 0.5),
                                        std::make_unique<Beckmann>(0.25));
    check_fidelity(make(ggx_beckmann, "sliced-matching"), ggx_beckmann, 1, 1, 2.5);
    const AnisotropicBlend sincs(std::make_unique<SincNdf>(6.0, 0.05, 128),
                                 std::make_unique<SincNdf>(3.5, 0.02, 96));
    check_fidelity(make(sincs, "sliced-matching"), sincs, 1, 1, 2.5);
    // The per-direction path itself is exact for an elliptical target.
    std::vector<std::unique_ptr<Ndf>> one;
    one.push_back(std::make_unique<Beckmann>(0.2, 0.6));
    const MixtureNdf wrapped(std::move(one), {1.0});
    check_fidelity(make(wrapped, "sliced-matching"), wrapped, 1, 1, 0);
}

TEST_CASE("sliced matching keeps the axes of an anisotropic NDF") {
    const Beckmann aniso(0.2, 0.6);
    check_fidelity(make(aniso, "sliced-matching"), aniso, 0.2, 0.6, 0);
    // A brushed target, 7:1. Integrated in the plain metric, this diverged (x slopes 0.5 after
    // 100 iterations, 3e4 after 200); the stretched metric keeps it at the ideal bar.
    const Beckmann brushed(0.05, 0.35);
    check_fidelity(make(brushed, "sliced-matching"), brushed, 0.05, 0.35, 0);
}

TEST_CASE("Heitz and constrained generators follow Beckmann too") {
    // Bar: within three times the mean distance of an ideal independent sample, and the
    // effective alpha within 3 %. Their surfaces are correlated by construction: one Gaussian
    // realisation with ~(256/8)^2 correlation patches, or a lattice of features kept by design
    // (measured: Heitz 2.7x, constrained 2.1x; docs/microsurfaces.md).
    const Beckmann beckmann(0.5);
    SurfaceSpec heitz;
    heitz.generator = &heitz_generator();
    heitz.size = 256;
    check_fidelity(generate_surface(beckmann, heitz, 2), beckmann, 0.5, 0.5, 3.0);
    for (const std::string c : {"domes", "holes"}) {
        CAPTURE(c);
        check_fidelity(make(beckmann, "sliced-matching", 0, 1, c), beckmann, 0.5, 0.5, 3.0);
    }
}

TEST_CASE("the Schwarz error falls and the surface is periodic") {
    const Beckmann beckmann(0.5);
    for (const char* g : {"sliced-matching", "algorithm1"}) {
        GenerationLog log;
        const HeightField h = make(beckmann, g, 50, 1, "none", &log);
        CAPTURE(g);
        REQUIRE(log.schwarz_mean.size() == 51);
        CHECK(log.schwarz_mean.back() < 0.5 * log.schwarz_mean.front());
        CHECK(log.above_threshold.back() < log.above_threshold.front());
        // The step across the wrap is like any other step: the mean |p| of the wrapping column
        // (and |q| of the wrapping row) lies within 4 standard deviations of the spread of all
        // column (row) means. Neighbouring steps are correlated, so the spread is measured.
        for (int axis = 0; axis < 2; ++axis) {
            std::vector<double> means(h.n, 0.0);
            for (int a = 0; a < h.n; ++a)
                for (int b = 0; b < h.n; ++b)
                    means[a] += std::abs(axis == 0 ? h.p(a, b) : h.q(b, a)) / h.n;
            double mu = 0, var = 0;
            for (int a = 0; a + 1 < h.n; ++a) mu += means[a] / (h.n - 1);
            for (int a = 0; a + 1 < h.n; ++a) var += (means[a] - mu) * (means[a] - mu) / (h.n - 2);
            CAPTURE(axis);
            CHECK(std::abs(means[h.n - 1] - mu) < 4 * std::sqrt(var));
        }
    }
}

TEST_CASE("same seed, same heights with 1 and 2 threads, and another seed, another surface") {
    const Ggx ggx(0.3);
    for (const char* g : {"sliced-matching", "algorithm1"}) {
        SurfaceSpec s;
        s.size = 128;
        s.iterations = 30;
        s.generator = &generator_named(g);
        HeightField one, two;
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
            one = generate_surface(ggx, s, 1);
        }
        two = generate_surface(ggx, s, 2);
        CAPTURE(g);
        CHECK(one.h == two.h);
        s.seed = 2;
        CHECK(generate_surface(ggx, s, 2).h != two.h);
    }
    // The pool's path, and a target that is not shape-invariant (the fixed directions' tables).
    const AnisotropicBlend blend(std::make_unique<Ggx>(0.5, 0.5), std::make_unique<Beckmann>(0.25));
    for (MatchTarget target : {MatchTarget::pool, MatchTarget::quantiles}) {
        SurfaceSpec s;
        s.size = 128;
        s.iterations = 30;
        s.target = target;
        HeightField one;
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
            one = generate_surface(blend, s, 1);
        }
        CHECK(one.h == generate_surface(blend, s, 2).h);
        CHECK(generate_surface(ggx, s, 2).h == generate_surface(ggx, s, 1).h);
    }
}

TEST_CASE("EXR height maps round-trip with their attributes, and bad files give clear errors") {
    const fs::path dir = fs::temp_directory_path() / ("gonio_exr_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    HeightField s(32, 0.25);
    Rng rng{5};
    for (float& v : s.h) v = float(rng.uniform() * 3 - 1);
    ExrAttributes a;
    a.text["gonio_ndf"] = "beckmann(alpha_x=0.5, alpha_y=0.5)";
    a.numbers["gonio_iterations"] = 500;
    const std::string path = (dir / "h.exr").string();
    write_height_exr(path, s, a);
    ExrAttributes back;
    const HeightField r = read_height_exr(path, &back);
    CHECK(r.n == 32);
    CHECK(r.spacing == 0.25);
    CHECK(r.h == s.h);
    CHECK(back.text["gonio_ndf"] == a.text["gonio_ndf"]);
    CHECK(back.numbers["gonio_iterations"] == 500);

    CHECK_THROWS_WITH_AS(read_height_exr((dir / "none.exr").string()),
                         doctest::Contains("none.exr: no such height map"), std::runtime_error);
    std::ofstream(dir / "bad.exr") << "this is not an EXR file";
    CHECK_THROWS_WITH_AS(read_height_exr((dir / "bad.exr").string()),
                         doctest::Contains("bad.exr: cannot read height map"), std::runtime_error);
    write_channels_exr((dir / "rect.exr").string(), 4, 2, {"Y"}, {std::vector<float>(8, 0.0f)}, {});
    CHECK_THROWS_WITH_AS(read_height_exr((dir / "rect.exr").string()),
                         doctest::Contains("must be square"), std::runtime_error);
    fs::remove_all(dir);
}

TEST_CASE("the surface cache returns the same surface and never regenerates it") {
    const fs::path dir = fs::temp_directory_path() / ("gonio_cache_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const SurfaceCache cache(dir.string());
    const Beckmann ndf(0.5);
    SurfaceSpec spec;
    spec.size = 64;
    spec.iterations = 20;
    SurfaceOrigin first, second, other, off;
    const HeightField a = obtain_surface(ndf, spec, cache, 2, first);
    const HeightField b = obtain_surface(ndf, spec, cache, 2, second);
    CHECK(first.generated);
    CHECK(second.from_cache);
    CHECK(!second.generated);
    CHECK(a.h == b.h);
    REQUIRE(second.log.schwarz_mean.size() == first.log.schwarz_mean.size());
    for (size_t k = 0; k < first.log.schwarz_mean.size(); ++k)
        CHECK(second.log.schwarz_mean[k] ==
              doctest::Approx(first.log.schwarz_mean[k]).epsilon(1e-9));
    spec.iterations = 21; // anything that defines the surface changes the key
    obtain_surface(ndf, spec, cache, 2, other);
    CHECK(other.generated);
    CHECK(other.cache_path != first.cache_path);
    obtain_surface(ndf, spec, SurfaceCache(""), 2, off); // disabled
    CHECK(off.generated);
    fs::remove_all(dir);
}

TEST_CASE("a non-periodic measured map is detected and can be made periodic by mirroring") {
    HeightField ramp(32, 1.0);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) ramp.h[size_t(y) * 32 + x] = float(0.1 * x + 0.05 * y);
    CHECK(seam_ratio(ramp) > 10);
    const HeightField tiled = mirror_tile(ramp);
    CHECK(tiled.n == 64);
    CHECK(seam_ratio(tiled) < 1.01);
    const fs::path dir = fs::temp_directory_path() / ("gonio_input_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    write_height_exr((dir / "ramp.exr").string(), ramp, {});
    SurfaceSpec spec;
    spec.input = (dir / "ramp.exr").string();
    spec.edges = Edges::mirror;
    SurfaceOrigin origin;
    const HeightField loaded = obtain_surface(Beckmann(0.5), spec, SurfaceCache(""), 1, origin);
    CHECK(origin.loaded);
    CHECK(origin.warning.find("is not periodic") != std::string::npos);
    CHECK(origin.edges.find("mirror") == 0);
    CHECK(loaded.n == 64);
    fs::remove_all(dir);
}

TEST_CASE("generation can stop when the NDF distance stops improving") {
    const Beckmann beckmann(0.5);
    SurfaceSpec s;
    s.size = 64;
    s.iterations = 2000;
    s.stop_when_converged = true;
    GenerationLog log;
    generate_surface(beckmann, s, 2, &log);
    CHECK(log.converged_early);
    CHECK(log.iterations < 2000);
    CHECK(log.iterations % 10 == 0);
    REQUIRE(log.ndf_distance.size() >= 4);
    // Stopped after three checks without a 0.1 % improvement on the best distance.
    const double best = *std::min_element(log.ndf_distance.begin(), log.ndf_distance.end() - 3);
    for (size_t k = log.ndf_distance.size() - 3; k < log.ndf_distance.size(); ++k)
        CHECK(log.ndf_distance[k] >= best * (1 - 1e-3));
}

TEST_CASE("the cache key covers every parameter that defines a surface") {
    const Beckmann b(0.5);
    SurfaceSpec base;
    const std::string k0 = surface_cache_key(b, base);
    auto differs = [&](SurfaceSpec s) { return surface_cache_key(b, s) != k0; };
    SurfaceSpec s = base;
    s.size = 128;
    CHECK(differs(s));
    s = base, s.spacing = 2;
    CHECK(differs(s));
    s = base, s.iterations = 499;
    CHECK(differs(s));
    s = base, s.threshold = 0.03;
    CHECK(differs(s));
    s = base, s.seed = 2;
    CHECK(differs(s));
    s = base, s.generator = &algorithm1_generator();
    CHECK(differs(s));
    s = base, s.constraint = Constraint::domes;
    CHECK(differs(s));
    s = base, s.stop_when_converged = true;
    CHECK(differs(s));
    s = base, s.target = MatchTarget::pool;
    CHECK(differs(s));
    SurfaceSpec d = base;
    d.constraint = Constraint::domes;
    const std::string kd = surface_cache_key(b, d);
    d.lattice = 4;
    CHECK(surface_cache_key(b, d) != kd);
    SurfaceSpec h = base;
    h.generator = &heitz_generator();
    const std::string kh = surface_cache_key(b, h);
    h.correlation_length = 4;
    CHECK(surface_cache_key(b, h) != kh);
    CHECK(surface_cache_key(Beckmann(0.51), base) != k0);
    CHECK(surface_cache_key(Ggx(0.5), base) != k0);
}
