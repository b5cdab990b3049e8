#pragma once
// Small vector and angle helpers shared by every library.
// Frame convention (docs/architecture.md): macro-surface normal n = +z, directions point away from the surface,
// theta from +z, phi from +x counter-clockwise. Code speaks radians.
#include <algorithm>
#include <cmath>

namespace gonio {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;
inline constexpr double kInvPi = 1.0 / kPi;

inline constexpr double radians(double degrees) {
    return degrees * (kPi / 180.0);
}
inline constexpr double degrees(double radians) {
    return radians * (180.0 / kPi);
}

struct Vec3 {
    double x = 0, y = 0, z = 0;
    constexpr Vec3() = default;
    constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
};
inline constexpr Vec3 operator*(double s, const Vec3& v) {
    return v * s;
}
inline constexpr double dot(const Vec3& a, const Vec3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& v) {
    return std::sqrt(dot(v, v));
}
inline Vec3 normalize(const Vec3& v) {
    return v * (1.0 / length(v)); // one division (a hot path of the tracer)
}

// Unit vector of spherical angles (radians).
inline Vec3 spherical_direction(double theta, double phi) {
    const double s = std::sin(theta);
    return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}
// theta in [0, pi], from z clamped to [-1, 1].
inline double spherical_theta(const Vec3& v) {
    return std::acos(std::clamp(v.z, -1.0, 1.0));
}
// phi in [0, 2 pi).
inline double spherical_phi(const Vec3& v) {
    const double p = std::atan2(v.y, v.x);
    return p < 0 ? p + kTwoPi : p;
}
// Angle between two unit vectors, accurate for small angles (unlike acos of the dot product).
inline double angle_between(const Vec3& a, const Vec3& b) {
    return dot(a, b) >= 0 ? 2.0 * std::asin(std::min(1.0, length(a - b) / 2))
                          : kPi - 2.0 * std::asin(std::min(1.0, length(a + b) / 2));
}
// Mirror reflection of v about the normal m (both pointing away from the surface).
inline constexpr Vec3 reflect(const Vec3& v, const Vec3& m) {
    return 2.0 * dot(v, m) * m - v;
}

} // namespace gonio
