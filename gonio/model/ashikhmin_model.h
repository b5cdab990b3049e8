#pragma once
// Ashikhmin, Premoze and Shirley's BRDF generator [A00]: from any distribution of normals p(h),
// a specular BRDF whose shadowing needs only g(k) = int_{h.k > 0} (h.k) p(h) dw_h [A00 Eq. 18]:
//   rho_s(k1, k2) = p(h) P(k1, k2, h) F(k.h) / (4 (k1.n)(k2.n) <h.n>)           [A00 Eq. 11]
//   P(k) = (k.n) <h.n> / g(k)                                                  [A00 Eq. 25]
// with P(k1, k2, h) = P(k1) P(k2) (uncorrelated, giving [A00 Eq. 26]) or the correlated
// (1 - t) P(k1) P(k2) + t min(P(k1), P(k2)), t a Gaussian in the azimuth between k1 and k2
// [A00 Eq. 14]; and an optional diffuse term that takes what the specular part leaves,
// c (1 - R(k1))(1 - R(k2)) rho_d [A00 Eq. 28-30] (or, for metals, f0 in place of the ones and of
// rho_d [A00 section 5.1]), R(k) being the specular directional albedo [A00 Eq. 29].
// g and R are tabulated over the directions by numerical integration (theta only when p is
// isotropic) and interpolated bilinearly, as A00 section 5.2 does. p need not be normalised.
#include "core/enum_names.h"
#include "gonio/material/fresnel_term.h"
#include "gonio/model/brdf_model.h"
#include "heightfield/ndf/ndf.h"

#include <functional>
#include <string>
#include <vector>

namespace gonio {

// A distribution of normals as A00 takes it: any non-negative function on the upper hemisphere.
struct NormalDensity {
    std::function<double(const Vec3&)> p;
    double narrowest = 0.1, widest = 0.5; // angular feature widths (radians), as Ndf's
    std::string description;
};
// p = D of a gonio NDF (a height field's distribution).
NormalDensity density_of(const Ndf& ndf);
// A00 section 6.3: satin, 0.7 p_flats + 0.3 p_ends, "cylindrical" Gaussians of slope widths 0.1
// and 0.3 across the fibres (x) and infinite along them, each normalised.
NormalDensity satin_density();
// A00 Eq. 35: velvet, the "inverse Gaussian" c exp(-cot^2 theta / sigma^2).
NormalDensity velvet_density(double sigma);

// The diffuse term that takes what the specular part leaves: none, a dielectric's [A00 Eq. 28-30]
// or a metal's [A00 section 5.1].
enum class AshikhminDiffuse { none, dielectric, metal };
template <>
struct EnumNames<AshikhminDiffuse> {
    static constexpr const char* what = "diffuse term";
    static constexpr const char* names[] = {"none", "dielectric", "metal"};
};

struct AshikhminSettings {
    double correlation_width = 0; // radians; 0: uncorrelated [A00 Eq. 13]
    AshikhminDiffuse diffuse = AshikhminDiffuse::none;
    std::vector<double> rho_d{1.0};       // dielectric diffuse albedo, one or one per channel
    int theta_nodes = 61, phi_nodes = 32; // table resolution (phi only for anisotropic p)
};

class AshikhminModel final : public BrdfModel {
  public:
    // Tabulates g and R (seconds for an anisotropic p, on all cores). Throws
    // std::invalid_argument for a bad setting.
    AshikhminModel(NormalDensity p, FresnelTerm fresnel, AshikhminSettings settings);

    int channels() const override { return fresnel_.channels(); }
    void eval_cosine(const Vec3& i, const Vec3& o, double* out) const override;
    double narrowest_feature() const override { return p_.narrowest; }
    double widest_feature() const override { return p_.widest; }

    void specular_cosine(const Vec3& i, const Vec3& o, double* out) const; // rho_s cos(theta_o)
    double g(const Vec3& k) const;                                         // table [A00 Eq. 18]
    double g_exact(const Vec3& k) const;                                   // by quadrature
    double mean_cosine() const { return mean_cos_; }                       // <h.n> (unnormalised)
    // R(k) [A00 Eq. 29]: from the table with a diffuse term, otherwise by quadrature.
    double reflectance(const Vec3& k, int channel) const;
    double reflectance_exact(const Vec3& k, int channel) const;
    bool isotropic() const { return phi_nodes_ == 1; }

  private:
    double table(const std::vector<double>& t, const Vec3& k, int stride, int offset) const;

    NormalDensity p_;
    FresnelTerm fresnel_;
    AshikhminSettings s_;
    double mean_cos_ = 1;
    int theta_nodes_ = 0, phi_nodes_ = 1;
    std::vector<double> g_, r_;          // [theta][phi], [theta][phi][channel]
    std::vector<double> diffuse_scale_;  // c per channel [A00 Eq. 28]
    std::vector<double> diffuse_level_;  // 1 (dielectric) or f0 (metal) per channel
    std::vector<double> diffuse_albedo_; // rho_d (dielectric) or f0 (metal) per channel
};

} // namespace gonio
