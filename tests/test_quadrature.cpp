#include "core/chi_square.h"
#include "core/math.h"
#include "core/quadrature.h"

#include <cmath>
#include <doctest/doctest.h>

using namespace gonio;

TEST_CASE("Gauss-Legendre is exact for polynomials of degree 2n-1") {
    for (int n : {1, 2, 3, 4, 7, 16, 64}) {
        const GaussLegendre& r = gauss_legendre(n);
        for (int deg = 0; deg <= 2 * n - 1; ++deg) {
            double sum = 0;
            for (int k = 0; k < n; ++k) sum += r.weights[k] * std::pow(r.nodes[k], deg);
            const double exact = deg % 2 ? 0.0 : 2.0 / (deg + 1);
            CHECK(sum == doctest::Approx(exact).epsilon(1e-13));
        }
    }
}

TEST_CASE("adaptive Gauss-Kronrod integrates peaks and kinks") {
    CHECK(integrate_adaptive([](double x) { return std::exp(-x); }, 0, 30) ==
          doctest::Approx(1 - std::exp(-30.0)).epsilon(1e-11));
    CHECK(integrate_adaptive([](double x) { return std::abs(x - 0.3); }, 0, 1) ==
          doctest::Approx(0.5 * (0.09 + 0.49)).epsilon(1e-10));
    // A narrow Gaussian: found when the interval is split at the feature, as callers do
    // (a peak that no node of the first rules samples cannot be found; see quadrature.h).
    const double s = 1e-3;
    auto peak = [s](double x) { return std::exp(-0.5 * (x - 0.1) * (x - 0.1) / (s * s)); };
    CHECK(integrate_adaptive(peak, 0, 0.1) + integrate_adaptive(peak, 0.1, 1) ==
          doctest::Approx(s * std::sqrt(kTwoPi)).epsilon(1e-9));
}

TEST_CASE("chi-square p-values match tabulated critical values") {
    // 5% critical values of the chi-square distribution.
    CHECK(chi_square_p_value(3.841458820694124, 1) == doctest::Approx(0.05).epsilon(1e-9));
    CHECK(chi_square_p_value(18.307038053275146, 10) == doctest::Approx(0.05).epsilon(1e-9));
    CHECK(chi_square_p_value(124.34211340400407, 100) == doctest::Approx(0.05).epsilon(1e-9));
    CHECK(sidak_level(0.01, 1) == doctest::Approx(0.01));
    CHECK(sidak_level(0.01, 10) < 0.01 / 9.9);
}
