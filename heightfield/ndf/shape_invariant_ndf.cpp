#include "heightfield/ndf/shape_invariant_ndf.h"

#include "core/check.h"
#include "core/number_text.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace gonio {

ShapeInvariantNdf::ShapeInvariantNdf(double alpha_x, double alpha_y) : ax_(alpha_x), ay_(alpha_y) {
    GONIO_DCHECK(alpha_x > 0 && alpha_y > 0 && std::isfinite(alpha_x) && std::isfinite(alpha_y));
}

double ShapeInvariantNdf::D(const Vec3& m) const {
    if (m.z <= 0) return 0.0;
    const double cos2 = m.z * m.z;
    // Stretched squared slope (R19 Eq. 6): tan^2 theta (cos^2 phi / ax^2 + sin^2 phi / ay^2).
    const double r2 = ((m.x / ax_) * (m.x / ax_) + (m.y / ay_) * (m.y / ay_)) / cos2;
    return d_unit(r2, cos2) / (ax_ * ay_);
}

double ShapeInvariantNdf::lambda(const Vec3& v) const {
    if (v.z <= 0) return std::numeric_limits<double>::infinity();
    // alpha_v^2 tan^2 theta_v with alpha_v^2 = ax^2 cos^2 phi + ay^2 sin^2 phi [M18 Eq. 20 text].
    const double t2 = ((ax_ * v.x) * (ax_ * v.x) + (ay_ * v.y) * (ay_ * v.y)) / (v.z * v.z);
    return lambda_unit(t2);
}

Vec3 ShapeInvariantNdf::sample_m(double u1, double u2) const {
    // Radius from the radial CDF, azimuth uniform, then stretch [M18 Eq. 29-31 in slope form].
    const double r = std::sqrt(sample_slope_radius2(u1));
    const double phi = kTwoPi * u2;
    const double p = ax_ * r * std::cos(phi), q = ay_ * r * std::sin(phi);
    return normalize(Vec3{-p, -q, 1.0});
}

Vec3 ShapeInvariantNdf::sample_visible(const Vec3& v, double u1, double u2) const {
    // Heitz & d'Eon 2014, Algorithm 1: stretch, sample unit-roughness slopes, rotate, unstretch.
    const Vec3 vs = normalize(Vec3{ax_ * v.x, ay_ * v.y, v.z});
    const double sin_t = std::sqrt(vs.x * vs.x + vs.y * vs.y);
    const double cos_phi = sin_t > 0 ? vs.x / sin_t : 1.0;
    const double sin_phi = sin_t > 0 ? vs.y / sin_t : 0.0;
    double x, y;
    sample_visible_slope(vs.z, u1, u2, x, y);
    const double px = cos_phi * x - sin_phi * y, py = sin_phi * x + cos_phi * y;
    return normalize(Vec3{-ax_ * px, -ay_ * py, 1.0});
}

std::string ShapeInvariantNdf::describe() const {
    std::ostringstream s;
    s << name() << "(alpha_x=" << shortest(ax_) << ", alpha_y=" << shortest(ay_) << ")";
    return s.str();
}

double ShapeInvariantNdf::narrowest_feature() const {
    return std::min(ax_, ay_);
}
double ShapeInvariantNdf::widest_feature() const {
    return std::max(ax_, ay_);
}

} // namespace gonio
