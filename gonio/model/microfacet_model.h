#pragma once
// The specular microfacet BRDF, "Model L1" [R19 Eq. 2]:
//   f(i, o) = F(i.h) D(h) G2(i, o, h) / (4 |i.n| |o.n|),   h = (i + o) / |i + o|,
// with G2 height-correlated [R19 Eq. 9] or uncorrelated [R19 Eq. 3].
#include "gonio/material/fresnel_term.h"
#include "gonio/model/brdf_model.h"
#include "heightfield/ndf/ndf.h"

#include <cstdint>
#include <utility>

namespace gonio {

class MicrofacetModel final : public BrdfModel {
  public:
    // Keeps a reference to ndf, which must outlive the model; copies the (small) Fresnel term.
    MicrofacetModel(const Ndf& ndf, FresnelTerm fresnel, MaskingForm masking)
        : ndf_(ndf), fresnel_(std::move(fresnel)), masking_(masking), id_(next_id()) {}

    int channels() const override { return fresnel_.channels(); }
    const Ndf& ndf() const { return ndf_; }
    MaskingForm masking() const { return masking_; }

    void eval_cosine(const Vec3& i, const Vec3& o, double* out) const override;
    double narrowest_feature() const override { return ndf_.narrowest_feature(); }
    double widest_feature() const override { return ndf_.widest_feature(); }

  private:
    static std::uint64_t next_id();
    double lambda_i(const Vec3& i) const; // Lambda(i), remembered per thread for the last i

    const Ndf& ndf_;
    FresnelTerm fresnel_;
    MaskingForm masking_;
    std::uint64_t id_; // unique per model ever made: keys the per-thread Lambda(i) cache
};

} // namespace gonio
