#include "heightfield/ndf/ndf.h"

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
        return std::min({1.0, 2.0 * i.z * m.z / im, 2.0 * o.z * m.z / om});
    const double li = lambda_i, lo = lambda(o);
    if (std::isinf(li) || std::isinf(lo)) return 0.0;
    if (form == MaskingForm::height_correlated) return 1.0 / (1.0 + li + lo); // R19 Eq. 9
    return 1.0 / ((1.0 + li) * (1.0 + lo));                                   // R19 Eq. 3
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

} // namespace gonio
