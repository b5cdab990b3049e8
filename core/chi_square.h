#pragma once
// Pearson chi-square goodness-of-fit test, shared by every sampler test.
#include <string>
#include <vector>

namespace gonio {

// Regularised upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a), a > 0, x >= 0.
double gamma_q(double a, double x);
// P(X^2 >= statistic) for a chi-square variable with `dof` degrees of freedom.
double chi_square_p_value(double statistic, int dof);

struct ChiSquareResult {
    double statistic = 0;
    int dof = 0;
    double p_value = 1;
    int pooled_bins = 0; // bins with expected < min_expected, merged into one
    std::string failure; // non-empty: an impossible observation (count where none expected)
};

// Bins whose expected count is below min_expected are pooled into one bin (pbrt-v4, Mitsuba 3).
// A bin observed but expected (almost) empty is reported in `failure`.
ChiSquareResult chi_square_test(const std::vector<double>& observed,
                                const std::vector<double>& expected, double min_expected = 5.0);

// Per-test significance level for `tests` independent tests at family level `alpha` (Sidak).
double sidak_level(double alpha, int tests);

} // namespace gonio
