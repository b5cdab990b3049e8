#include "core/quadrature.h"

#include "core/math.h"

#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <queue>
#include <stdexcept>

namespace gonio {

const GaussLegendre& gauss_legendre(int n) {
    if (n < 1 || n > 512) throw std::invalid_argument("gauss_legendre: n must be in [1, 512]");
    static std::mutex mutex;
    static std::map<int, GaussLegendre> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(n);
    if (it != cache.end()) return it->second;
    GaussLegendre rule;
    rule.nodes.resize(n);
    rule.weights.resize(n);
    if (n == 1) {
        rule.nodes[0] = 0;
        rule.weights[0] = 2;
        return cache.emplace(n, std::move(rule)).first->second;
    }
    // Newton iteration on P_n from the Tricomi initial guess of each root.
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
        double dp = 0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16) break;
        }
        // Recompute the derivative at the converged root for the weight.
        double p0 = 1, p1 = x;
        for (int k = 2; k <= n; ++k) {
            const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
            p0 = p1;
            p1 = p2;
        }
        dp = n * (x * p1 - p0) / (x * x - 1);
        const double w = 2 / ((1 - x * x) * dp * dp);
        rule.nodes[i] = -x;
        rule.nodes[n - 1 - i] = x;
        rule.weights[i] = rule.weights[n - 1 - i] = w;
    }
    return cache.emplace(n, std::move(rule)).first->second;
}

namespace {

// Kronrod 15-point nodes on [0, 1] (symmetric), with Kronrod and embedded Gauss 7-point weights.
constexpr std::array<double, 8> kXk = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr std::array<double, 8> kWk = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr std::array<double, 4> kWg = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

void gk15(const std::function<double(double)>& f, double a, double b, double& k, double& g) {
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    const double fc = f(c);
    k = kWk[7] * fc;
    g = kWg[3] * fc;
    for (int j = 0; j < 7; ++j) {
        const double dx = h * kXk[j];
        const double s = f(c - dx) + f(c + dx);
        k += kWk[j] * s;
        if (j % 2 == 1) g += kWg[j / 2] * s;
    }
    k *= h;
    g *= h;
}

double adapt(const std::function<double(double)>& f, double a, double b, double whole_k,
             double whole_g, double tol, int depth) {
    if (std::abs(whole_k - whole_g) <= tol || depth <= 0 || !(b - a > 0)) return whole_k;
    const double m = 0.5 * (a + b);
    double k1, g1, k2, g2;
    gk15(f, a, m, k1, g1);
    gk15(f, m, b, k2, g2);
    return adapt(f, a, m, k1, g1, 0.5 * tol, depth - 1) +
           adapt(f, m, b, k2, g2, 0.5 * tol, depth - 1);
}

} // namespace

double integrate_adaptive(const std::function<double(double)>& f, double a, double b,
                          double abs_tol, double rel_tol, int max_depth) {
    if (a == b) return 0;
    double k, g;
    gk15(f, a, b, k, g);
    // A coarse 4-piece pass sets the scale for the relative tolerance robustly.
    double scale = 0;
    for (int j = 0; j < 4; ++j) {
        double kj, gj;
        gk15(f, a + (b - a) * j / 4, a + (b - a) * (j + 1) / 4, kj, gj);
        scale += kj;
    }
    const double tol = std::max(abs_tol, rel_tol * std::abs(scale));
    return adapt(f, a, b, k, g, tol, max_depth);
}

double integrate_global(const std::function<double(double)>& f, double a, double b, double abs_tol,
                        double rel_tol, int max_pieces) {
    if (a == b) return 0;
    struct Piece {
        double a, b, k, err;
        bool operator<(const Piece& o) const { return err < o.err; }
    };
    std::priority_queue<Piece> pieces;
    double k, g, total = 0, error = 0;
    gk15(f, a, b, k, g);
    pieces.push({a, b, k, std::abs(k - g)});
    total = k, error = std::abs(k - g);
    while (error > std::max(abs_tol, rel_tol * std::abs(total)) &&
           int(pieces.size()) < max_pieces) {
        const Piece p = pieces.top();
        pieces.pop();
        const double m = 0.5 * (p.a + p.b);
        if (!(m > p.a && m < p.b)) { // cannot split further: keep it as it is
            pieces.push({p.a, p.b, p.k, 0.0});
            error -= p.err;
            continue;
        }
        double k1, g1, k2, g2;
        gk15(f, p.a, m, k1, g1);
        gk15(f, m, p.b, k2, g2);
        pieces.push({p.a, m, k1, std::abs(k1 - g1)});
        pieces.push({m, p.b, k2, std::abs(k2 - g2)});
        total += k1 + k2 - p.k;
        error += std::abs(k1 - g1) + std::abs(k2 - g2) - p.err;
    }
    // Re-sum the pieces (the running sums collect round-off).
    total = 0;
    while (!pieces.empty()) total += pieces.top().k, pieces.pop();
    return total;
}

double integrate_adaptive_2d(const std::function<double(double, double)>& f, double x0, double x1,
                             const std::function<double(double)>& y0,
                             const std::function<double(double)>& y1, double abs_tol,
                             double rel_tol) {
    auto inner = [&](double x) {
        const double lo = y0(x), hi = y1(x);
        if (!(hi > lo)) return 0.0;
        return integrate_adaptive([&](double y) { return f(x, y); }, lo, hi, abs_tol, rel_tol);
    };
    return integrate_adaptive(inner, x0, x1, abs_tol, rel_tol);
}

} // namespace gonio
