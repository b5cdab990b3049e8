// The NDF battery for the radial generalised family (Student's t, generalised normal, the two-shape
// generalised t): normalisation, Lambda against brute force [R19 Eq. 5], visible-normal
// normalisation, chi-square tests of both samplers, the family's limits, and parameter checks.
#include "chi_square_harness.h"
#include "core/config_error.h"
#include "core/hemisphere_integral.h"
#include "gonio/config/config.h"
#include "heightfield/ndf/anisotropic_blend.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/gaussian_angles.h"
#include "heightfield/ndf/generalized_normal.h"
#include "heightfield/ndf/generalized_t.h"
#include "heightfield/ndf/ggx.h"
#include "heightfield/ndf/mixture_ndf.h"
#include "heightfield/ndf/ndf_table.h"
#include "heightfield/ndf/piecewise_linear.h"
#include "heightfield/ndf/sinc_ndf.h"
#include "heightfield/ndf/student_t.h"
#include "heightfield/ndf/tabulated_ndf.h"

#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

using namespace gonio;
using gonio::hemisphere_integral;

namespace {
std::vector<std::unique_ptr<Ndf>> family() {
    std::vector<std::unique_ptr<Ndf>> out;
    out.push_back(std::make_unique<StudentT>(0.5, 0.5, 2.2)); // heavy tails, near the limit
    out.push_back(std::make_unique<StudentT>(0.3, 0.7, 3.0)); // anisotropic
    out.push_back(std::make_unique<StudentT>(0.5, 0.5, 20.0));
    out.push_back(std::make_unique<GeneralizedNormal>(0.5, 0.5, 0.5)); // peaked
    out.push_back(std::make_unique<GeneralizedNormal>(0.4, 0.4, 1.0));
    out.push_back(std::make_unique<GeneralizedNormal>(0.3, 0.6, 8.0)); // flat-topped
    out.push_back(std::make_unique<GeneralizedT>(0.5, 0.5, 1.5, 3.0));
    out.push_back(std::make_unique<GeneralizedT>(0.4, 0.4, 4.0, 0.6));
    out.push_back(std::make_unique<PiecewiseLinearNdf>(
        PiecewiseLinearNdf::sampled_from(StudentT(0.4, 0.4, 3.0), 64)));
    out.push_back(std::make_unique<SincNdf>(6.0, 0.05, 128)); // multi-lobe
    // Rough: 3 % of its peak at the 89.9 deg cut. (At sigma = 1 the chi-square reference, Gauss-
    // Legendre in cos theta per cell, cannot integrate the visible pdf's 1/cos growth up to the
    // cut.)
    out.push_back(std::make_unique<GaussianAngles>(0.6));
    // R19 Eq. 10: two sinc curves, and GGX along x with Beckmann along y.
    out.push_back(std::make_unique<AnisotropicBlend>(std::make_unique<SincNdf>(6.0, 0.05, 128),
                                                     std::make_unique<SincNdf>(3.5, 0.02, 96)));
    out.push_back(std::make_unique<AnisotropicBlend>(std::make_unique<Ggx>(0.5, 0.5),
                                                     std::make_unique<Beckmann>(0.25)));
    std::vector<std::unique_ptr<Ndf>> parts;
    parts.push_back(std::make_unique<Beckmann>(0.15));
    parts.push_back(std::make_unique<StudentT>(0.3, 0.6, 3.0));
    out.push_back(std::make_unique<MixtureNdf>(std::move(parts), std::vector<double>{1.0, 2.0}));
    // A measured-like table: anisotropic Student's t on a 3 x 15 degree grid.
    out.push_back(
        std::make_unique<TabulatedNdf>(sample_ndf_table(StudentT(0.3, 0.5, 4.0), 30, 24), "t"));
    return out;
}

// Polar angles where D is not smooth: a piecewise-linear NDF's control points.
std::vector<double> kinks(const Ndf& ndf) {
    if (const auto* pl = dynamic_cast<const PiecewiseLinearNdf*>(&ndf)) return pl->points().theta;
    if (const auto* g = dynamic_cast<const GaussianAngles*>(&ndf)) return {g->theta_max()};
    std::vector<double> out;
    if (const auto* table = dynamic_cast<const TabulatedNdf*>(&ndf))
        for (int j = 1; j < table->table().theta_intervals; ++j)
            out.push_back(0.5 * kPi * j / table->table().theta_intervals);
    auto add = [&](const Ndf& part) {
        const std::vector<double> k = kinks(part);
        out.insert(out.end(), k.begin(), k.end());
    };
    if (const auto* blend = dynamic_cast<const AnisotropicBlend*>(&ndf)) {
        add(blend->along_x());
        add(blend->along_y());
    }
    if (const auto* mix = dynamic_cast<const MixtureNdf*>(&ndf))
        for (size_t k = 0; k < mix->size(); ++k) add(mix->component(k));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// Azimuths where D is not smooth: a table's columns.
std::vector<double> phi_kinks(const Ndf& ndf) {
    std::vector<double> out;
    if (const auto* table = dynamic_cast<const TabulatedNdf*>(&ndf))
        for (int k = 1; k < table->table().phi_count; ++k)
            out.push_back(kTwoPi * k / table->table().phi_count);
    return out;
}

bool anisotropic(const Ndf& ndf) {
    const double d0 = ndf.D(spherical_direction(0.6, 0.0));
    for (double phi : {0.5, 1.2, 0.5 * kPi})
        if (std::abs(ndf.D(spherical_direction(0.6, phi)) - d0) > 1e-9 * d0) return true;
    return false;
}
} // namespace

TEST_CASE("NDF battery: normalisation of the generalised family") {
    for (const auto& ndf : family()) {
        CAPTURE(ndf->describe());
        const double integral = hemisphere_integral([&](const Vec3& m) { return ndf->D(m) * m.z; },
                                                    ndf->narrowest_feature(), nullptr, 1e-10,
                                                    kinks(*ndf), phi_kinks(*ndf));
        CHECK(std::abs(integral - 1.0) < 1e-4);
        CHECK(std::abs(integral - 1.0) < 1e-6);
    }
}

TEST_CASE("NDF battery: tabulated Lambda of the generalised family against R19 Eq. 5") {
    for (const auto& ndf : family()) {
        for (double theta_deg : {0.0, 30.0, 60.0, 85.0, 89.9}) {
            for (double phi_deg :
                 anisotropic(*ndf) ? std::vector<double>{0, 30, 90} : std::vector<double>{20}) {
                const Vec3 v = spherical_direction(radians(theta_deg), radians(phi_deg));
                const double integral = hemisphere_integral(
                    [&](const Vec3& m) { return std::max(0.0, dot(v, m)) * ndf->D(m); },
                    ndf->narrowest_feature(), &v, 1e-10, kinks(*ndf), phi_kinks(*ndf));
                const double brute = integral / v.z - 1.0, lambda = ndf->lambda(v);
                CAPTURE(ndf->describe());
                CAPTURE(theta_deg);
                CAPTURE(phi_deg);
                CAPTURE(lambda);
                CAPTURE(brute);
                CHECK(std::abs(brute - lambda) <= 1e-5 * (1 + lambda)); // the 1e-5
            }
        }
    }
}

TEST_CASE("NDF battery: visible normals of the generalised family are normalised") {
    for (const auto& ndf : family()) {
        for (double theta_deg : {0.0, 45.0, 85.0}) {
            const Vec3 v = spherical_direction(radians(theta_deg), radians(30.0));
            const double integral = hemisphere_integral(
                [&](const Vec3& m) { return ndf->pdf_visible(v, m); }, ndf->narrowest_feature(), &v,
                1e-10, kinks(*ndf), phi_kinks(*ndf));
            CAPTURE(ndf->describe());
            CAPTURE(theta_deg);
            CHECK(std::abs(integral - 1.0) < 1e-5);
        }
    }
}

TEST_CASE("NDF battery: both samplers of the generalised family pass chi-square tests") {
    // 15 distributions x (D cos + visible from 2 angles), Sidak-corrected at 1 %.
    constexpr int kTests = 45, kSamples = 400000, kCells = 1001;
    std::uint64_t seed = 7;
    auto check = [&](const test::DirectionChiSquare& r, const std::string& what) {
        CAPTURE(what);
        CAPTURE(r.chi.statistic);
        CAPTURE(r.chi.dof);
        CAPTURE(r.chi.p_value);
        CAPTURE(r.chi.failure);
        CHECK(r.chi.failure.empty());
        CHECK(r.chi.p_value > sidak_level(0.01, kTests));
    };
    for (const auto& ndf : family()) {
        check(test::chi_square_directions([&](double a, double b) { return ndf->sample_m(a, b); },
                                          [&](const Vec3& m) { return ndf->pdf_m(m); }, kSamples,
                                          kCells, seed++),
              ndf->describe() + " D cos");
        for (double theta_deg : {40.0, 85.0}) {
            const Vec3 v = spherical_direction(radians(theta_deg), radians(30.0));
            check(test::chi_square_directions(
                      [&](double a, double b) { return ndf->sample_visible(v, a, b); },
                      [&](const Vec3& m) { return ndf->pdf_visible(v, m); }, kSamples, kCells,
                      seed++),
                  ndf->describe() + " visible from " + std::to_string(theta_deg));
        }
    }
}

TEST_CASE("Student's t: gamma = 2 is GGX, gamma = 1e4 is Beckmann within 1e-3") {
    const StudentT t2(0.3, 0.6, 2.0), t_big(0.5, 0.5, 1e4);
    const Ggx ggx(0.3, 0.6);
    const Beckmann beckmann(0.5);
    for (double t : {0.0, 0.2, 0.7, 1.2, 1.5}) {
        for (double p : {0.0, 0.7, 2.0}) {
            const Vec3 d = spherical_direction(t, p);
            CHECK(t2.D(d) == doctest::Approx(ggx.D(d)).epsilon(1e-12));
            CHECK(t2.lambda(d) == doctest::Approx(ggx.lambda(d)).epsilon(1e-8));
            const double peak = beckmann.D({0, 0, 1});
            CHECK(std::abs(t_big.D(d) - beckmann.D(d)) <= 1e-3 * peak);
            // G1 = 1 / (1 + Lambda) within 1e-3.
            CHECK(std::abs(t_big.lambda(d) - beckmann.lambda(d)) <=
                  1e-3 * (1 + beckmann.lambda(d)));
        }
    }
}

TEST_CASE("the two-shape generalised t: Student's t at p = 2, the generalised normal as q grows") {
    const GeneralizedT gt_std(0.4, 0.4, 2.0, 2.5), gt_gnd(0.4, 0.4, 1.5, 1e6);
    const StudentT std_(0.4, 0.4, 3.5);
    const GeneralizedNormal gnd(0.4, 0.4, 1.5);
    for (double t : {0.0, 0.3, 0.8, 1.3}) {
        const Vec3 d = spherical_direction(t, 0.4);
        CHECK(gt_std.D(d) == doctest::Approx(std_.D(d)).epsilon(1e-10));
        CHECK(gt_std.lambda(d) == doctest::Approx(std_.lambda(d)).epsilon(1e-7));
        CHECK(gt_gnd.D(d) == doctest::Approx(gnd.D(d)).epsilon(1e-4));
        CHECK(gt_gnd.lambda(d) == doctest::Approx(gnd.lambda(d)).epsilon(1e-4));
    }
}

TEST_CASE("the generalised family: Smith terms finite and monotone, limits rejected clearly") {
    for (const auto& ndf : family()) {
        CAPTURE(ndf->describe());
        CHECK(ndf->lambda({0, 0, 1}) == 0.0);
        CHECK(ndf->G1({1, 0, 0}) == 0.0);
        double previous = -1;
        for (double t = 0; t < kPi / 2; t += 0.01) {
            const double l = ndf->lambda(spherical_direction(t, 0.3));
            CHECK(std::isfinite(l));
            CHECK(l >= previous);
            previous = l;
        }
    }
    // Outside their ranges the parameters are refused where the config is read, naming the key
    // and its range (the constructors only DCHECK what the keys guarantee).
    auto error = [](const std::string& ndf) {
        try {
            parse_config("[beam]\ntheta_i = 0\n[ndf]\nalpha = 0.5\n" + ndf, "t.toml");
        } catch (const ConfigError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    for (const std::string gamma : {"1.9", "1.5", "1.01", "1.0", "0.5", "2e6", "nan"}) {
        const std::string e = error("type = \"student_t\"\ngamma = " + gamma + "\n");
        CHECK(e.find("key 'ndf.gamma'") != std::string::npos);
    }
    for (const std::string p : {"0.1", "0.49", "25.0", "nan"}) {
        const std::string e = error("type = \"generalized_normal\"\np = " + p + "\n");
        CHECK(e.find("key 'ndf.p'") != std::string::npos);
        CHECK(e.find("[0.5, 20]") != std::string::npos);
    }
    CHECK(error("type = \"generalized_t\"\np = 1.0\nq = 1.9\n").find("p q must be >= 2") !=
          std::string::npos);
    CHECK(error("type = \"generalized_t\"\np = 2.0\nq = 0.0\n").find("key 'ndf.q'") !=
          std::string::npos);
}

TEST_CASE("a piecewise-linear copy of Beckmann converges to it at second order") {
    // R19 Eq. 11-12 with n intervals uniform in theta: linear interpolation errs by O(h^2), so
    // doubling n should divide the errors in D, Lambda and the sampled slopes by about 4.
    const Beckmann beckmann(0.5);
    std::vector<double> d_err, lambda_err, sample_err;
    for (int n : {16, 32, 64, 128}) {
        const PiecewiseLinearNdf copy(PiecewiseLinearNdf::sampled_from(beckmann, n));
        double d = 0, l = 0, q = 0;
        for (double t = 0; t < 1.5; t += 0.01) {
            const Vec3 m = spherical_direction(t, 0.3);
            d = std::max(d, std::abs(copy.D(m) - beckmann.D(m)) / beckmann.D({0, 0, 1}));
        }
        for (double t : {0.5, 1.0, 1.3})
            l = std::max(l, std::abs(copy.lambda(spherical_direction(t, 0.0)) -
                                     beckmann.lambda(spherical_direction(t, 0.0))));
        for (double u = 0.05; u < 1; u += 0.1) // the same quantile of both inverse CDFs
            q = std::max(q, angle_between(copy.sample_m(u, 0.3), beckmann.sample_m(u, 0.3)));
        d_err.push_back(d), lambda_err.push_back(l), sample_err.push_back(q);
    }
    for (size_t k = 1; k < d_err.size(); ++k) {
        CAPTURE(k);
        CAPTURE(d_err[k - 1]);
        CAPTURE(d_err[k]);
        CAPTURE(lambda_err[k]);
        CAPTURE(sample_err[k]);
        CHECK(d_err[k - 1] / d_err[k] > 3.0);
        CHECK(lambda_err[k - 1] / lambda_err[k] > 3.0);
        CHECK(sample_err[k - 1] / sample_err[k] > 3.0);
    }
    CHECK(d_err.back() < 2e-3);
}

TEST_CASE("piecewise-linear normalisation: R19 Eq. 12 in closed form, and bad curves rejected") {
    // A constant curve D = 1: c = 2 pi int sin cos = pi.
    const ControlPoints flat{{0, 0.3, kPi / 2}, {1, 1, 1}};
    CHECK(piecewise_linear_normalisation(flat) == doctest::Approx(kPi).epsilon(1e-14));
    auto message = [](ControlPoints p) {
        try {
            PiecewiseLinearNdf ndf(p);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(message({{0, 1}, {1, 1}}).find("from 0 to 90 deg") != std::string::npos);
    CHECK(message({{0, 0.5, 0.4, kPi / 2}, {1, 1, 1, 1}}).find("must increase") !=
          std::string::npos);
    CHECK(message({{0, kPi / 2}, {1, -1}}).find(">= 0") != std::string::npos);
    CHECK(message({{0, kPi / 2}, {0, 0}}).find("zero everywhere") != std::string::npos);
}

TEST_CASE("Gaussian of angles: C numerically, and the small-sigma series") {
    for (double sigma : {0.05, 0.1, 0.2, 0.3}) {
        CAPTURE(sigma);
        const double exact = GaussianAngles::inverse_normalisation(sigma);
        CHECK(GaussianAngles::inverse_normalisation_series(sigma) ==
              doctest::Approx(exact).epsilon(1e-5));
    }
    // Normalised, with a finite, increasing Lambda (the battery checks it against brute force).
    const GaussianAngles n(0.3);
    CHECK(gonio::hemisphere_integral([&](const Vec3& m) { return n.D(m) * m.z; }, 0.3, nullptr,
                                     1e-10) == doctest::Approx(1.0).epsilon(1e-6));
    double previous = -1;
    for (double t = 0; t < kPi / 2; t += 0.05) {
        const double l = n.lambda(spherical_direction(t, 0.0));
        CHECK(std::isfinite(l));
        CHECK(l >= previous);
        previous = l;
    }
    // The cut keeps Lambda finite; without it the projected area diverges like ln(1 / (pi/2 -
    // theta_max)) (gaussian_angles.h): Lambda grows by about that law as the cut nears 90 deg.
    const Vec3 v = spherical_direction(radians(60), 0);
    const double l1 = GaussianAngles(1.0, radians(89.9)).lambda(v),
                 l2 = GaussianAngles(1.0, radians(89.99)).lambda(v),
                 l3 = GaussianAngles(1.0, radians(89.999)).lambda(v);
    CHECK(l2 > l1);
    CHECK(l3 > l2);
    // Each decade adds 2 C exp(-(pi/2)^2 / 2 sigma^2) tan theta_v ln 10 (the 1/cos tail's share).
    const double c = 1 / GaussianAngles::inverse_normalisation(1.0, radians(89.99));
    const double step = 2 * c * std::exp(-kPi * kPi / 8) * std::tan(radians(60)) * std::log(10.0);
    CHECK((l2 - l1) == doctest::Approx(step).epsilon(0.01));
    CHECK((l3 - l2) == doctest::Approx(step).epsilon(0.01));
    // sigma_Beckmann = sqrt(2) sigma_Gauss [M18 section 2]: similar lobes for small sigma.
    const GaussianAngles g(0.1);
    const Beckmann b(0.1 * std::sqrt(2.0));
    CHECK(g.D({0, 0, 1}) == doctest::Approx(b.D({0, 0, 1})).epsilon(1e-2));
}
