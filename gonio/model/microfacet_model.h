#pragma once
// The specular microfacet BRDF, "Model L1" [R19 Eq. 2]:
//   f(i, o) = F(i.h) D(h) G2(i, o, h) / (4 |i.n| |o.n|),   h = (i + o) / |i + o|,
// with G2 height-correlated [R19 Eq. 9] or uncorrelated [R19 Eq. 3].
#include "gonio/material/fresnel_term.h"
#include "heightfield/ndf/ndf.h"

#include <utility>

namespace gonio {

class MicrofacetModel {
  public:
    // Keeps a reference to ndf, which must outlive the model; copies the (small) Fresnel term.
    MicrofacetModel(const Ndf& ndf, FresnelTerm fresnel, MaskingForm masking)
        : ndf_(ndf), fresnel_(std::move(fresnel)), masking_(masking) {}

    int channels() const { return fresnel_.channels(); }
    const Ndf& ndf() const { return ndf_; }
    MaskingForm masking() const { return masking_; }

    // f(i, o) in sr^-1 per channel (0 if i or o is at or below the horizon).
    void eval(const Vec3& i, const Vec3& o, double* f) const;
    // f(i, o) cos(theta_o) per channel: the integrand of the albedo, finite up to the horizon.
    void eval_cosine(const Vec3& i, const Vec3& o, double* out) const;

  private:
    const Ndf& ndf_;
    FresnelTerm fresnel_;
    MaskingForm masking_;
};

} // namespace gonio
