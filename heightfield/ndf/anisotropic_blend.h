#pragma once
// The anisotropic blend of two isotropic NDFs of R19 section 3: D_x along phi = 0 and D_y along
// phi = pi/2,
//   D(m) = (cos^2 phi D_x(theta) D_y(0) + sin^2 phi D_y(theta) D_x(0)) / c,
//   c = (D_x(0) + D_y(0)) / 2                                           [R19 Eq. 10].
// Any two isotropic distributions of gonio may be blended (piecewise-linear curves as in the paper,
// or analytic ones: GGX along x and Beckmann along y).
//
// - Lambda from the projected area I(o) = int <o.m> D dw [R19 Eq. 13]: writing cos^2 phi =
//   (1 + cos 2 phi) / 2, each component contributes its own isotropic projected area
//   P(theta_o) = cos theta_o (1 + Lambda_iso) and cos(2 phi_o) K(theta_o), with
//   K = int <o.m> D_iso cos(2 phi_m) dw at phi_o = 0. The azimuthal integrals are closed-form on
//   the split domain of R19 Eq. 14 (C = acos(-cot theta_o cot theta_m)); the ratio K / P, which
//   depends on theta_o only, is tabulated per component and interpolated.
// - D cos sampling: phi_m by inverting R19 Eq. 16 with bracketed Newton, then theta_m from the
//   component chosen with probability proportional to its term of Eq. 10 at phi_m (Eq. 15).
// - Visible normals: exactly, by rejection from the envelope (D_y(0) D_x + D_x(0) D_y) / c >= D,
//   whose visible normals are those of a component; acceptance >= 1/2.
#include "heightfield/ndf/ndf.h"

#include <memory>
#include <vector>

namespace gonio {

class AnisotropicBlend final : public Ndf {
  public:
    // Both must be isotropic, and D_x(0) + D_y(0) > 0. Throws std::invalid_argument otherwise.
    AnisotropicBlend(std::unique_ptr<Ndf> along_x, std::unique_ptr<Ndf> along_y);

    double D(const Vec3& m) const override;
    double lambda(const Vec3& v) const override;
    Vec3 sample_m(double u1, double u2) const override;
    bool continuous_sampler() const override { return false; } // picks a part or rejects
    Vec3 sample_visible(const Vec3& v, double u1, double u2) const override;
    std::string name() const override { return "blend"; }
    std::string describe() const override;
    double narrowest_feature() const override;
    double widest_feature() const override;

    const Ndf& along_x() const { return *x_.ndf; }
    const Ndf& along_y() const { return *y_.ndf; }
    // phi in [0, 2 pi) with cdf(phi) = u [R19 Eq. 16].
    double sample_phi(double u) const;

  private:
    struct Component {
        std::unique_ptr<Ndf> ndf;
        double d0 = 0;                // D(theta = 0)
        std::vector<double> k_over_p; // K / P at theta_o = j (pi/2) / (size - 1)
    };
    static Component prepare(std::unique_ptr<Ndf> ndf, const char* axis);
    double k_over_p(const Component& c, double theta) const;

    Component x_, y_;
    double c_; // R19 Eq. 10
};

} // namespace gonio
