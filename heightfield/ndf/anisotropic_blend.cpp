#include "heightfield/ndf/anisotropic_blend.h"

#include "core/catmull_rom.h"
#include "core/parallel.h"
#include "core/quadrature.h"
#include "core/random.h"
#include "heightfield/ndf/ndf_family.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gonio {

namespace {
constexpr int kIntervals = 512; // polar angles of the K / P tables, minus one

Vec3 polar(double theta, double phi) {
    const double s = std::sin(theta);
    return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}

} // namespace

AnisotropicBlend::Component AnisotropicBlend::prepare(std::unique_ptr<Ndf> ndf, const char* axis) {
    if (!ndf) throw std::invalid_argument(std::string("blend: missing the ") + axis + " curve");
    if (!ndf->isotropic())
        throw std::invalid_argument(std::string("blend: the ") + axis + " curve (" +
                                    ndf->describe() + ") must be isotropic [R19 Eq. 10]");
    Component c;
    c.d0 = ndf->D({0, 0, 1});
    c.k_over_p.assign(kIntervals + 1, 0.0);
    const Ndf& d = *ndf;
    // P and K of the header, with the azimuthal integrals of R19 Eq. 14 in closed form:
    // for a = cos t_o cos t_m < b = sin t_o sin t_m only |psi| < C = acos(-a / b) sees o.
    parallel_for(1, kIntervals + 1, [&](int j) {
        const double to = 0.5 * kPi * j / kIntervals, co = std::cos(to), so = std::sin(to);
        const double split = 0.5 * kPi - to;
        auto lit = [&](double tm) {
            return 2 * kPi * co * std::cos(tm) * d.D(polar(tm, 0)) * std::sin(tm);
        };
        auto part = [&](double tm, bool k) {
            const double a = co * std::cos(tm), b = so * std::sin(tm);
            const double cc = std::acos(std::clamp(-a / b, -1.0, 1.0)),
                         w = d.D(polar(tm, 0)) * std::sin(tm);
            return w * (k ? a * std::sin(2 * cc) + b * (std::sin(3 * cc) / 3 + std::sin(cc))
                          : 2 * (a * cc + b * std::sin(cc)));
        };
        const double p = (split > 0 ? integrate_global(lit, 0, split, 1e-300, 1e-11) : 0.0) +
                         integrate_global([&](double tm) { return part(tm, false); }, split,
                                          0.5 * kPi, 1e-300, 1e-11);
        const double k = integrate_global([&](double tm) { return part(tm, true); }, split,
                                          0.5 * kPi, 1e-300, 1e-11);
        c.k_over_p[j] = p > 0 ? k / p : 0.0;
    });
    c.ndf = std::move(ndf);
    return c;
}

AnisotropicBlend::AnisotropicBlend(std::unique_ptr<Ndf> along_x, std::unique_ptr<Ndf> along_y)
    : x_(prepare(std::move(along_x), "x (phi = 0)")),
      y_(prepare(std::move(along_y), "y (phi = pi/2)")), c_(0.5 * (x_.d0 + y_.d0)) {
    if (!(c_ > 0) || !std::isfinite(c_))
        throw std::invalid_argument(
            "blend: D_x(0) + D_y(0) must be positive and finite [R19 Eq. 10]");
}

double AnisotropicBlend::k_over_p(const Component& c, double theta) const {
    return catmull_rom(c.k_over_p, theta / (0.5 * kPi) * kIntervals);
}

double AnisotropicBlend::D(const Vec3& m) const {
    if (m.z <= 0) return 0.0;
    const double s2 = m.x * m.x + m.y * m.y;
    const double cos2 = s2 > 0 ? m.x * m.x / s2 : 0.5, sin2 = 1.0 - cos2;
    return (cos2 * x_.ndf->D(m) * y_.d0 + sin2 * y_.ndf->D(m) * x_.d0) / c_; // R19 Eq. 10
}

double AnisotropicBlend::lambda(const Vec3& v) const {
    if (v.z <= 0) return std::numeric_limits<double>::infinity();
    const double lx = x_.ndf->lambda(v), ly = y_.ndf->lambda(v);
    if (std::isinf(lx) || std::isinf(ly)) return std::numeric_limits<double>::infinity();
    const double s2 = v.x * v.x + v.y * v.y;
    const double cos2phi = s2 > 0 ? (v.x * v.x - v.y * v.y) / s2 : 0.0;
    const double theta = std::acos(std::min(1.0, v.z));
    // I / cos theta_o = 1 + Lambda (R19 section 3.1), term by term of Eq. 10.
    const double ax = y_.d0 * (1 + lx) * (1 + cos2phi * k_over_p(x_, theta));
    const double ay = x_.d0 * (1 + ly) * (1 - cos2phi * k_over_p(y_, theta));
    return std::max(0.0, 0.5 * (ax + ay) / c_ - 1.0);
}

double AnisotropicBlend::sample_phi(double u) const {
    // cdf(phi) = phi / 2pi + kappa sin 2 phi [R19 Eq. 16]; it equals j/4 at phi = j pi/2, so the
    // quarter holding u brackets the root, and Newton steps are kept inside the bracket.
    const double kappa = (y_.d0 - x_.d0) / (4 * kPi * (y_.d0 + x_.d0));
    const int quarter = std::min(3, static_cast<int>(4 * u));
    double lo = quarter * 0.5 * kPi, hi = lo + 0.5 * kPi, phi = kTwoPi * u;
    for (int it = 0; it < 100; ++it) {
        const double f = phi / kTwoPi + kappa * std::sin(2 * phi) - u;
        if (f > 0)
            hi = phi;
        else
            lo = phi;
        const double df = 1 / kTwoPi + 2 * kappa * std::cos(2 * phi);
        double next = phi - f / df;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - phi) < 1e-15 * kTwoPi) return next;
        phi = next;
    }
    return phi;
}

Vec3 AnisotropicBlend::sample_m(double u1, double u2) const {
    const double phi = sample_phi(u1);
    // Given phi, theta's density is the mixture of the components' (R19 Eq. 15), weighted by
    // their terms of Eq. 10.
    const double c = std::cos(phi), wx = c * c * y_.d0, wy = (1 - c * c) * x_.d0;
    const double px = wx + wy > 0 ? wx / (wx + wy) : 0.5; // 0 / 0 only on a zero-density azimuth
    const bool use_x = u2 < px;
    const double u = use_x ? u2 / px : (u2 - px) / (1 - px);
    // Isotropic distributions of gonio draw theta from their first uniform, phi from the second.
    const Vec3 m = (use_x ? x_ : y_).ndf->sample_m(std::min(u, std::nextafter(1.0, 0.0)), 0.0);
    return polar(std::acos(std::clamp(m.z, -1.0, 1.0)), phi);
}

Vec3 AnisotropicBlend::sample_visible(const Vec3& v, double u1, double u2) const {
    // Envelope E = (D_y(0) D_x + D_x(0) D_y) / c: its visible normals come from component k with
    // probability proportional to its weight times its projected area cos theta_v (1 + Lambda_k).
    const double ex = y_.d0 * (1 + x_.ndf->lambda(v)), ey = x_.d0 * (1 + y_.ndf->lambda(v));
    const double px = ex / (ex + ey);
    Rng rng{bits_of(u1), bits_of(u2), 0x626c656e64ull};
    for (bool first = true;; first = false) {
        double a = first ? u1 : rng.uniform(), b = first ? u2 : rng.uniform();
        const bool use_x = first ? a < px : rng.uniform() < px;
        if (first) a = std::min(use_x ? a / px : (a - px) / (1 - px), std::nextafter(1.0, 0.0));
        const Component& k = use_x ? x_ : y_;
        const Vec3 m = k.ndf->sample_visible(v, a, b);
        const double envelope = (y_.d0 * x_.ndf->D(m) + x_.d0 * y_.ndf->D(m)) / c_;
        if (rng.uniform() * envelope < D(m)) return m;
    }
}

std::string AnisotropicBlend::describe() const {
    return "blend(x: " + x_.ndf->describe() + "; y: " + y_.ndf->describe() + ")";
}

double AnisotropicBlend::narrowest_feature() const {
    return std::min(x_.ndf->narrowest_feature(), y_.ndf->narrowest_feature());
}

double AnisotropicBlend::widest_feature() const {
    return std::max(x_.ndf->widest_feature(), y_.ndf->widest_feature());
}

} // namespace gonio

namespace gonio {
namespace {
const Key kX = Key::table("x", "the isotropic curve along φ = 0").cited("R19 Eq. 10");
const Key kY = Key::table("y", "the isotropic curve along φ = 90°").cited("R19 Eq. 10");
} // namespace
const NdfFamily& blend_family() {
    static const NdfFamily f{
        "blend",
        "anisotropic blend of two isotropic curves [R19 Eq. 10]",
        {kX, kY},
        [](TableReader& r, int depth) -> std::unique_ptr<Ndf> {
            std::unique_ptr<Ndf> axes[2];
            for (int k = 0; k < 2; ++k) {
                const Key& key = k ? kY : kX;
                const NdfFamily* family = nullptr;
                axes[k] = read_ndf(r.table(key), depth + 1, &family);
                double ax = 1, ay = 1;
                const bool one_alpha = !axes[k]->slope_stretch(ax, ay) || ax == ay;
                if (!family->curve || !one_alpha)
                    r.fail(key.name, "must be an isotropic curve (one alpha; not a blend, mixture "
                                     "or table) [R19 Eq. 10]");
            }
            return std::make_unique<AnisotropicBlend>(std::move(axes[0]), std::move(axes[1]));
        }};
    return f;
}
} // namespace gonio
