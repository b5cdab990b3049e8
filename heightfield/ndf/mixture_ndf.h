#pragma once
// A weighted sum of distributions, D = sum_k w_k D_k with the weights normalised to sum 1.
//
// Lambda comes from the mixture's own projected area I(v) = int <v.m> D dw = sum_k w_k I_k(v)
// [R19 Eq. 5, 13], and I_k = cos theta_v (1 + Lambda_k) [R19 section 3.1], so
// 1 + Lambda = sum_k w_k (1 + Lambda_k) exactly. (Mixing the masking G1 = 1 / (1 + Lambda) instead
// would be wrong.) D cos sampling picks a component by weight; visible normals pick component k
// with probability proportional to w_k (1 + Lambda_k(v)), its share of the projected area, then use
// the component's own visible sampler: both exact.
#include "heightfield/ndf/ndf.h"

#include <memory>
#include <vector>

namespace gonio {

class MixtureNdf final : public Ndf {
  public:
    // At least one component; weights > 0 (any scale), one per component. Throws
    // std::invalid_argument otherwise.
    MixtureNdf(std::vector<std::unique_ptr<Ndf>> components, std::vector<double> weights);

    double D(const Vec3& m) const override;
    double lambda(const Vec3& v) const override;
    Vec3 sample_m(double u1, double u2) const override;
    bool continuous_sampler() const override { return false; } // picks a part or rejects
    Vec3 sample_visible(const Vec3& v, double u1, double u2) const override;
    std::string name() const override { return "mixture"; }
    std::string describe() const override;
    double narrowest_feature() const override;
    double widest_feature() const override;

    const std::vector<double>& weights() const { return weights_; } // normalised
    size_t size() const { return components_.size(); }
    const Ndf& component(size_t k) const { return *components_[k]; }

  private:
    std::vector<std::unique_ptr<Ndf>> components_;
    std::vector<double> weights_;
};

} // namespace gonio
