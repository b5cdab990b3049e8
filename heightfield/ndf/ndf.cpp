#include "heightfield/ndf/ndf.h"

#include "core/check.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gonio {

double Ndf::G1(const Vec3& v) const {
    const double l = lambda(v);
    return std::isinf(l) ? 0.0 : 1.0 / (1.0 + l); // R19 Eq. 8
}

double Ndf::G1(const Vec3& v, const Vec3& m) const {
    return dot(v, m) > 0 ? G1(v) : 0.0; // R19 Eq. 4
}

double Ndf::G2(const Vec3& i, const Vec3& o, const Vec3& m, MaskingForm form) const {
    if (dot(i, m) <= 0 || dot(o, m) <= 0) return 0.0; // back-facing: no Lambda needed
    return G2(i, o, m, form, form == MaskingForm::v_cavity ? 0.0 : lambda(i));
}

double Ndf::G2(const Vec3& i, const Vec3& o, const Vec3& m, MaskingForm form,
               double lambda_i) const {
    const double im = dot(i, m), om = dot(o, m);
    if (im <= 0 || om <= 0) return 0.0;
    if (form == MaskingForm::v_cavity) // M18 Eq. 15: exact for V-grooves along m's azimuth
        return i.z <= 0 || o.z <= 0 ? 0.0
                                    : std::min({1.0, 2.0 * i.z * m.z / im, 2.0 * o.z * m.z / om});
    return smith_g2(lambda_i, lambda(o), i, o, form);
}

double smith_g2(double li, double lo, const Vec3& i, const Vec3& o, MaskingForm form) {
    if (std::isinf(li) || std::isinf(lo)) return 0.0;
    switch (form) {
    case MaskingForm::height_correlated:
        return 1.0 / (1.0 + li + lo); // R19 Eq. 9
    case MaskingForm::uncorrelated:
        return 1.0 / ((1.0 + li) * (1.0 + lo)); // R19 Eq. 3
    case MaskingForm::height_direction_correlated: {
        // Heitz 2014 Eq. 101: phi in [0, pi] between the projections of i and o (a direction along
        // the normal has Lambda 0, so its azimuth does not matter).
        const double ri = std::hypot(i.x, i.y), ro = std::hypot(o.x, o.y);
        double phi = 0;
        if (ri > 0 && ro > 0)
            phi = std::acos(std::clamp((i.x * o.x + i.y * o.y) / (ri * ro), -1.0, 1.0));
        const double l = 4.41 * phi / (4.41 * phi + 1.0); // van Ginneken et al. 1998
        return 1.0 / (1.0 + std::max(li, lo) + l * std::min(li, lo));
    }
    case MaskingForm::v_cavity:
        break;
    }
    GONIO_CHECK_MSG(false, "smith_g2: the V-cavity form is not a Smith form");
    return 0.0;
}

double Ndf::pdf_m(const Vec3& m) const {
    return m.z > 0 ? D(m) * m.z : 0.0;
}

double Ndf::pdf_visible(const Vec3& v, const Vec3& m) const {
    if (v.z <= 0) return 0.0;
    const double vm = dot(v, m);
    if (vm <= 0) return 0.0;
    return G1(v) * vm * D(m) / v.z; // Heitz 2014, Eq. 16
}

bool Ndf::isotropic() const {
    for (double theta_deg : {3.0, 12.0, 27.0, 45.0, 63.0, 78.0, 86.0}) {
        const double reference = D(spherical_direction(radians(theta_deg), 0.0));
        for (double phi_deg : {17.0, 45.0, 90.0, 131.0, 200.0, 293.0}) {
            const double d = D(spherical_direction(radians(theta_deg), radians(phi_deg)));
            if (std::abs(d - reference) > 1e-9 * std::max(std::abs(reference), 1e-300))
                return false;
        }
    }
    return true;
}

} // namespace gonio
