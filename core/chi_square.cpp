#include "core/chi_square.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {
// Series for P(a, x), valid for x < a + 1.
double gamma_p_series(double a, double x) {
    double sum = 1.0 / a, term = sum;
    for (int n = 1; n < 10000; ++n) {
        term *= x / (a + n);
        sum += term;
        if (std::abs(term) < std::abs(sum) * 1e-16) break;
    }
    return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}
// Continued fraction (modified Lentz) for Q(a, x), valid for x >= a + 1.
double gamma_q_fraction(double a, double x) {
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < 1e-16) break;
    }
    return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}
} // namespace

double gamma_q(double a, double x) {
    if (!(a > 0) || x < 0) throw std::invalid_argument("gamma_q: needs a > 0 and x >= 0");
    if (x == 0) return 1;
    return x < a + 1 ? 1 - gamma_p_series(a, x) : gamma_q_fraction(a, x);
}

double chi_square_p_value(double statistic, int dof) {
    if (dof < 1) return 1;
    return gamma_q(0.5 * dof, 0.5 * statistic);
}

ChiSquareResult chi_square_test(const std::vector<double>& observed,
                                const std::vector<double>& expected, double min_expected) {
    if (observed.size() != expected.size())
        throw std::invalid_argument("chi_square_test: observed and expected differ in size");
    ChiSquareResult r;
    double pooled_obs = 0, pooled_exp = 0, total = 0;
    for (double e : expected) total += e;
    int bins = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 1e-9 * total) {
            if (observed[i] > 0 && r.failure.empty())
                r.failure = "bin " + std::to_string(i) + " observed " +
                            std::to_string(observed[i]) + " samples but expected " +
                            std::to_string(expected[i]);
            pooled_obs += observed[i];
            pooled_exp += expected[i];
            continue;
        }
        if (expected[i] < min_expected) {
            pooled_obs += observed[i];
            pooled_exp += expected[i];
            ++r.pooled_bins;
            continue;
        }
        const double d = observed[i] - expected[i];
        r.statistic += d * d / expected[i];
        ++bins;
    }
    if (pooled_exp > 0) {
        const double d = pooled_obs - pooled_exp;
        r.statistic += d * d / pooled_exp;
        ++bins;
    }
    r.dof = bins - 1;
    r.p_value = chi_square_p_value(r.statistic, r.dof);
    return r;
}

double sidak_level(double alpha, int tests) {
    return 1 - std::pow(1 - alpha, 1.0 / tests);
}

} // namespace gonio
