#pragma once
// The microfacet normal distribution interface. Every distribution of gonio implements it, so the
// surface generator, the analytic models and the simulator can use any of them.
//
// Conventions (docs/architecture.md): n = +z; D is normalised so that  integral D(m) (m.n) dw_m = 1
// [R19 Eq. 2 text]; Smith's masking G1(v) = 1 / (1 + Lambda(v)) [R19 Eq. 8]; directions are unit
// vectors.
#include "core/enum_names.h"
#include "core/math.h"

#include <string>

namespace gonio {

// Which Smith masking-shadowing term G2 the models use.
enum class MaskingForm {
    height_correlated, // G2 = 1 / (1 + Lambda(i) + Lambda(o))       [R19 Eq. 9]
    uncorrelated,      // G2 = G1(i) G1(o)                             [R19 Eq. 3]
    v_cavity,          // Torrance-Sparrow: min(1, 2 n.m n.i / i.m, 2 n.m n.o / o.m) [M18 Eq. 15]
    // G2 = 1 / (1 + max(Li, Lo) + l(phi) min(Li, Lo)), l(phi) = 4.41 phi / (4.41 phi + 1), phi the
    // azimuth between i and o [Heitz 2014 Eq. 101, after van Ginneken et al. 1998]
    height_direction_correlated,
};
template <>
struct EnumNames<MaskingForm> {
    static constexpr const char* what = "masking";
    static constexpr const char* names[] = {"height-correlated", "uncorrelated", "v-cavity",
                                            "height-direction-correlated"};
};

// Smith's joint masking-shadowing of a facet facing both i and o, from Lambda(i) and Lambda(o), in
// one of the Smith forms (not v_cavity). Infinite Lambdas give 0.
double smith_g2(double lambda_i, double lambda_o, const Vec3& i, const Vec3& o, MaskingForm form);

class Ndf {
  public:
    virtual ~Ndf() = default;

    // D(m) in sr^-1; 0 for m.z <= 0.
    virtual double D(const Vec3& m) const = 0;
    // Smith Lambda(v) for v.z > 0 (+infinity at or below the horizon) [R19 Eq. 8].
    virtual double lambda(const Vec3& v) const = 0;
    // A normal m with pdf D(m) m.z, from two uniforms in [0, 1).
    virtual Vec3 sample_m(double u1, double u2) const = 0;
    // A normal visible from v (v.z > 0) with pdf D_v(m) = G1(v) <v.m> D(m) / v.z (Heitz 2014).
    virtual Vec3 sample_visible(const Vec3& v, double u1, double u2) const = 0;
    // Short family name ("beckmann") and a full description with parameters.
    virtual std::string name() const = 0;
    virtual std::string describe() const = 0;
    // Angular widths of the narrowest and widest lobe features (radians, roughly the slope
    // standard deviation): the analytic models refine their quadrature down to this scale.
    virtual double narrowest_feature() const = 0;
    virtual double widest_feature() const = 0;
    // True when sample_m is a continuous map of (u1, u2) (an inverse CDF), so that quadrature rules
    // may be laid in its primary space; false for samplers that pick a part or reject.
    virtual bool continuous_sampler() const { return true; }
    // For shape-invariant distributions: true, with the roughness (alpha_x, alpha_y) that maps the
    // slopes to an isotropic unit-roughness distribution (p / alpha_x, q / alpha_y).
    virtual bool slope_stretch(double& alpha_x, double& alpha_y) const {
        (void)alpha_x, (void)alpha_y;
        return false;
    }
    // True when the slopes are a centred 2-D Gaussian (Beckmann), with its roughness: what a
    // random-phase Gaussian surface (the heitz generator) can follow.
    virtual bool gaussian_slopes(double& alpha_x, double& alpha_y) const {
        (void)alpha_x, (void)alpha_y;
        return false;
    }

    // G1(v) = 1 / (1 + Lambda(v)) [R19 Eq. 8].
    double G1(const Vec3& v) const;
    // G1(v, m): masking of a facet m seen from v, 0 for back-facing facets [R19 Eq. 4].
    double G1(const Vec3& v, const Vec3& m) const;
    // Masking-shadowing G2(i, o, m) in the chosen form [R19 Eq. 3 and Eq. 9, M18 Eq. 15].
    double G2(const Vec3& i, const Vec3& o, const Vec3& m, MaskingForm form) const;
    // The same with lambda_i = Lambda(i) given (a caller that holds i fixed computes it once).
    double G2(const Vec3& i, const Vec3& o, const Vec3& m, MaskingForm form, double lambda_i) const;
    // True when D is invariant under rotations about the normal, checked numerically (D at seven
    // polar angles and six azimuths agrees to 1e-9).
    bool isotropic() const;
    // pdf of sample_m: D(m) m.z.
    double pdf_m(const Vec3& m) const;
    // pdf of sample_visible: G1(v, m) <v.m> D(m) / v.z.
    double pdf_visible(const Vec3& v, const Vec3& m) const;
};

} // namespace gonio
