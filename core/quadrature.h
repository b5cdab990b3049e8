#pragma once
// Deterministic quadrature used by the analytic models and the tests.
#include <functional>
#include <vector>

namespace gonio {

// Gauss-Legendre rule with n nodes on [-1, 1] (exact for polynomials of degree 2n-1).
struct GaussLegendre {
    std::vector<double> nodes;
    std::vector<double> weights;
};
// n in [1, 512]; rules are computed once per n and cached (thread-safe).
const GaussLegendre& gauss_legendre(int n);

// Adaptive Gauss-Kronrod (7/15) integral of f over [a, b]. Subdivides until the Kronrod-Gauss
// difference of each piece is below max(abs_tol, rel_tol * |whole|) scaled by the piece's share
// of [a, b], or max_depth is reached. Like every adaptive rule it cannot find a feature that none
// of its first nodes sample: split [a, b] at known peaks and at kinks.
double integrate_adaptive(const std::function<double(double)>& f, double a, double b,
                          double abs_tol = 1e-12, double rel_tol = 1e-10, int max_depth = 40);

// Globally adaptive Gauss-Kronrod (7/15): always bisects the piece with the largest error
// estimate, until the summed estimate is below max(abs_tol, rel_tol * |integral|) or max_pieces
// pieces exist. Unlike integrate_adaptive it cannot blow up on an endpoint singularity or a
// non-smooth tail (its work is bounded), so it suits integrands mapped from [0, infinity).
double integrate_global(const std::function<double(double)>& f, double a, double b,
                        double abs_tol = 1e-300, double rel_tol = 1e-12, int max_pieces = 2000);

// Nested adaptive integral over x in [x0, x1], y in [y0(x), y1(x)].
double integrate_adaptive_2d(const std::function<double(double, double)>& f, double x0, double x1,
                             const std::function<double(double)>& y0,
                             const std::function<double(double)>& y1, double abs_tol = 1e-11,
                             double rel_tol = 1e-9);

} // namespace gonio
