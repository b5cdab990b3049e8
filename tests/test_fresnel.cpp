#include "core/math.h"
#include "gonio/material/fresnel.h"
#include "gonio/material/fresnel_term.h"
#include "gonio/material/ior_table.h"

#include <cmath>
#include <complex>
#include <doctest/doctest.h>

using namespace gonio;

namespace {
// Independent s and p amplitudes (Hecht, Optics, Eq. 4.42-4.45) for a real index ratio.
struct Amplitudes {
    double rs, rp, ts, tp, cos_t;
};
Amplitudes amplitudes(double cos_i, double eta) {
    const double sin_t = std::sqrt(1 - cos_i * cos_i) / eta;
    const double cos_t = std::sqrt(1 - sin_t * sin_t);
    return {(cos_i - eta * cos_t) / (cos_i + eta * cos_t),
            (eta * cos_i - cos_t) / (eta * cos_i + cos_t), 2 * cos_i / (cos_i + eta * cos_t),
            2 * cos_i / (eta * cos_i + cos_t), cos_t};
}
} // namespace

TEST_CASE("dielectric Fresnel at normal incidence") {
    CHECK(fresnel_dielectric(1.0, 1.5) == doctest::Approx(0.04).epsilon(1e-14));
    CHECK(fresnel_dielectric(1.0, 1.33) ==
          doctest::Approx(std::pow(0.33 / 2.33, 2)).epsilon(1e-14));
    CHECK(fresnel_dielectric(1.0, 1.0) == 0.0);
    CHECK(fresnel_dielectric(-1.0, 1.5) == doctest::Approx(0.04).epsilon(1e-14)); // from inside
    CHECK(fresnel_f0(1.5) == doctest::Approx(0.04));
}

TEST_CASE("dielectric Fresnel at Brewster's angle: only s-polarised light is reflected") {
    for (double eta : {1.33, 1.5, 2.4}) {
        const double cos_b = std::cos(std::atan(eta));
        const Amplitudes a = amplitudes(cos_b, eta);
        CHECK(std::abs(a.rp) < 1e-14);
        CHECK(fresnel_dielectric(cos_b, eta) == doctest::Approx(0.5 * a.rs * a.rs).epsilon(1e-12));
    }
}

TEST_CASE("dielectric Fresnel: total internal reflection beyond the critical angle") {
    const double eta = 1.0 / 1.5; // from glass to air
    const double cos_c = std::sqrt(1 - eta * eta);
    CHECK(fresnel_dielectric(cos_c * 0.999, eta) == 1.0);
    CHECK(fresnel_dielectric(0.0, eta) == 1.0);
    CHECK(fresnel_dielectric(-0.1, 1.5) == 1.0); // the same, seen as light arriving from inside
    CHECK(fresnel_dielectric(cos_c * 1.001, eta) < 1.0);
}

TEST_CASE("dielectric Fresnel conserves energy: R + T = 1") {
    for (double eta : {1.000001, 1.33, 1.5, 2.4, 4.0, 1 / 1.5}) {
        for (double t = 0; t < 90; t += 2.5) {
            const double c = std::cos(radians(t));
            if (eta < 1 && std::sqrt(1 - c * c) >= eta) continue; // TIR
            const Amplitudes a = amplitudes(c, eta);
            // Transmittance = (eta cos_t / cos_i) |t|^2, unpolarised mean.
            const double T = eta * a.cos_t / c * 0.5 * (a.ts * a.ts + a.tp * a.tp);
            CAPTURE(eta);
            CAPTURE(t);
            CHECK(fresnel_dielectric(c, eta) + T == doctest::Approx(1.0).epsilon(1e-12));
        }
    }
}

TEST_CASE("conductor Fresnel reduces to the dielectric one for k = 0, and to 1 at grazing") {
    for (double eta : {1.2, 1.5, 3.0})
        for (double c = 0.01; c <= 1.0; c += 0.07)
            CHECK(fresnel_conductor(c, {eta, 0.0}) ==
                  doctest::Approx(fresnel_dielectric(c, eta)).epsilon(1e-12));
    CHECK(fresnel_conductor(0.0, {0.2, 3.0}) == doctest::Approx(1.0));
}

TEST_CASE("conductor Fresnel against published closed forms and values") {
    // Normal incidence: R = ((n-1)^2 + k^2) / ((n+1)^2 + k^2) (Born & Wolf Eq. 14.2(19)).
    const std::complex<double> gold{0.21, 3.272}; // Johnson & Christy 1972 at 616.8 nm
    const double r0 = ((0.21 - 1) * (0.21 - 1) + 3.272 * 3.272) / ((1.21 * 1.21) + 3.272 * 3.272);
    CHECK(fresnel_conductor(1.0, gold) == doctest::Approx(r0).epsilon(1e-12));
    // Oblique incidence: the real-arithmetic form with a^2, b^2 (Born & Wolf section 14.2;
    // Cook & Torrance 1982 appendix), independent of the complex-angle implementation.
    const double n = 0.21, k = 3.272;
    for (double t = 0; t < 89.9; t += 7.3) {
        const double c = std::cos(radians(t)), s2 = 1 - c * c;
        const double u = n * n - k * k - s2, root = std::sqrt(u * u + 4 * n * n * k * k);
        const double a2 = 0.5 * (root + u), b2 = 0.5 * (root - u), a = std::sqrt(a2);
        const double rs = (a2 + b2 - 2 * a * c + c * c) / (a2 + b2 + 2 * a * c + c * c);
        const double sin_tan = s2 / c; // sin(theta) tan(theta)
        const double rp2 = rs * (a2 + b2 - 2 * a * sin_tan + sin_tan * sin_tan) /
                           (a2 + b2 + 2 * a * sin_tan + sin_tan * sin_tan);
        CAPTURE(t);
        CHECK(fresnel_conductor(c, {n, k}) == doctest::Approx(0.5 * (rs + rp2)).epsilon(1e-10));
    }
    // Published: evaporated aluminium reflects about 91.6 % at 550 nm at normal incidence
    // (McPeak et al. 2015 optical constants; Bass, Handbook of Optics vol. IV, Al ~ 91.5 %).
    const IorTable al = IorTable::load(resolve_ior_path("Al"));
    CHECK(fresnel_conductor(1.0, al.at(550)) == doctest::Approx(0.916).epsilon(0.003));
}

TEST_CASE("Schlick's approximation") {
    CHECK(fresnel_schlick(1.0, 0.04) == doctest::Approx(0.04)); // exact at normal incidence
    CHECK(fresnel_schlick(0.0, 0.04) == doctest::Approx(1.0));  // and at grazing incidence
    CHECK(fresnel_schlick(0.5, 0.04) == doctest::Approx(0.04 + 0.96 / 32.0));
    double previous = 2;
    for (double c = 0; c <= 1.0; c += 0.05) { // decreasing in cos(theta)
        CHECK(fresnel_schlick(c, 0.04) < previous);
        previous = fresnel_schlick(c, 0.04);
    }
}

TEST_CASE("refractive-index tables: interpolation, range and errors") {
    const IorTable au = IorTable::load(resolve_ior_path("Au"));
    CHECK(au.at(616.8).real() == doctest::Approx(0.21));
    CHECK(au.at(616.8).imag() == doctest::Approx(3.272));
    const auto mid = au.at(0.5 * (616.8 + 659.5));
    CHECK(mid.real() == doctest::Approx(0.5 * (0.21 + 0.14)));
    CHECK_THROWS_AS(au.at(100.0), std::out_of_range);
    CHECK_THROWS_AS(IorTable::load("/nonexistent/Xx.csv"), std::runtime_error);
    for (const char* metal : {"Au", "Ag", "Cu", "Al"}) {
        const IorTable t = IorTable::load(resolve_ior_path(metal));
        CHECK(t.source().find("source:") != std::string::npos); // every table names its source
        for (double w : {450.0, 550.0, 650.0}) {
            const double r = fresnel_conductor(1.0, t.at(w));
            CHECK(r > 0.3);
            CHECK(r < 1.0);
        }
    }
}

TEST_CASE("FresnelTerm evaluates one value per channel") {
    double out[3];
    FresnelTerm::mirror().eval(0.3, out);
    CHECK(out[0] == 1.0);
    const FresnelTerm c = FresnelTerm::conductor({{0.2, 3.0}, {0.5, 2.5}, {1.4, 1.9}});
    REQUIRE(c.channels() == 3);
    c.eval(0.5, out);
    CHECK(out[2] == fresnel_conductor(0.5, {1.4, 1.9}));
    FresnelTerm::dielectric({1.5}).eval(1.0, out);
    CHECK(out[0] == doctest::Approx(0.04));
}
