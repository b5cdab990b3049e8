#pragma once
// Inverses of the error functions, to double precision (bracketed Newton on std::erfc).
#include <algorithm>
#include <cmath>

namespace gonio {

// s >= 0 with erfc(s) = t, for t in (0, 1]; t <= 0 gives a large finite s.
inline double erfc_inverse_upper(double t) {
    if (t >= 1) return 0;
    t = std::max(t, 1e-300);
    double lo = 0, hi = 27; // erfc(27) < 1e-300
    // Initial guess from the tail asymptote erfc(s) ~ exp(-s^2) / (s sqrt(pi)).
    double s = std::sqrt(std::max(0.0, -std::log(t * 1.7724538509055160)));
    s = std::clamp(s, lo, hi);
    for (int i = 0; i < 200; ++i) {
        const double h = std::erfc(s) - t;
        if (h > 0)
            lo = s;
        else
            hi = s;
        const double dh = -1.1283791670955126 * std::exp(-s * s); // d erfc / ds
        double next = dh != 0 ? s - h / dh : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - s) <= 1e-15 * (1 + s)) return next;
        s = next;
    }
    return s;
}

// x with (1 + erf(x)) / 2 = u, for u in [0, 1): the inverse CDF of a normal of variance 1/2.
inline double erf_quantile(double u) {
    return u < 0.5 ? -erfc_inverse_upper(2 * u) : erfc_inverse_upper(2 * (1 - u));
}

} // namespace gonio
