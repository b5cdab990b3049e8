#include "gonio/material/interfaced_lambertian.h"

#include "core/check.h"
#include "core/quadrature.h"
#include "gonio/material/fresnel.h"
#include "gonio/material/material_kind.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {
std::vector<double> per_channel(std::vector<double> v, size_t n) {
    if (v.size() == 1) v.assign(n, v[0]);
    return v;
}
} // namespace

double InterfacedLambertianFacet::diffuse_reflectance(double eta) {
    if (eta == 1.0) return 0.0;
    return integrate_adaptive(
        [eta](double t) { return fresnel_dielectric(std::cos(t), eta) * std::sin(2 * t); }, 0.0,
        0.5 * kPi, 1e-15, 1e-12); // M18 Eq. 10 with the external reflectance
}

double InterfacedLambertianFacet::molenaar_reflectance(double n) {
    const double n2 = n * n, n4 = n2 * n2; // M18 Eq. 11
    return 0.5 - 2 * n2 * n * (n2 + 2 * n - 1) / ((n2 + 1) * (n4 - 1)) +
           (n - 1) * (3 * n + 1) / (6 * (n + 1) * (n + 1)) +
           8 * n4 * (n4 + 1) / ((n2 + 1) * (n4 - 1) * (n4 - 1)) * std::log(n) +
           n2 * (n2 - 1) * (n2 - 1) / ((n2 + 1) * (n2 + 1) * (n2 + 1)) *
               std::log((n - 1) / (n + 1));
}

InterfacedLambertianFacet::InterfacedLambertianFacet(std::vector<double> eta,
                                                     std::vector<double> albedo) {
    const size_t n = std::max(eta.size(), albedo.size());
    if (eta.empty() || albedo.empty() || (eta.size() != n && eta.size() != 1) ||
        (albedo.size() != n && albedo.size() != 1))
        throw std::invalid_argument("interfaced_lambertian: give one eta and one albedo, or one "
                                    "per channel");
    eta_ = per_channel(std::move(eta), n);
    kd_ = per_channel(std::move(albedo), n);
    for (size_t k = 0; k < n; ++k) {
        if (!(eta_[k] >= 1 && eta_[k] <= 100))
            throw std::invalid_argument("interfaced_lambertian: eta must be in [1, 100]");
        if (!(kd_[k] >= 0 && kd_[k] <= 1))
            throw std::invalid_argument("interfaced_lambertian: albedo must be in [0, 1]");
        re_.push_back(diffuse_reflectance(eta_[k]));
        ri_.push_back(1 - (1 - re_[k]) / (eta_[k] * eta_[k])); // M18: n^2 (1 - r_i) = 1 - r_e
    }
}

double InterfacedLambertianFacet::body_brdf(const Vec3& i, const Vec3& o, const Vec3& m,
                                            int k) const {
    const double ci = dot(i, m), co = dot(o, m);
    if (ci <= 0 || co <= 0) return 0.0;
    const double ti = 1 - fresnel_dielectric(ci, eta_[k]), to = 1 - fresnel_dielectric(co, eta_[k]);
    return ti * to * kd_[k] / (kPi * eta_[k] * eta_[k] * (1 - kd_[k] * ri_[k])); // M18 Eq. 9
}

double InterfacedLambertianFacet::albedo(const Vec3& i, const Vec3& m, int k) const {
    const double f = fresnel_dielectric(std::max(0.0, dot(i, m)), eta_[k]);
    return f + (1 - f) * kd_[k] * (1 - ri_[k]) / (1 - kd_[k] * ri_[k]);
}

bool InterfacedLambertianFacet::scatter(const Vec3& wi, const Vec3& m, Rng& rng, Vec3& wo,
                                        double* weight) const {
    const double ci = std::max(0.0, dot(wi, m));
    const int n = channels();
    GONIO_DCHECK(n <= kMaxChannels); // spectrum.wavelengths' limit
    double f[kMaxChannels], specular = 0;
    for (int k = 0; k < n; ++k)
        specular = std::max(specular, f[k] = fresnel_dielectric(ci, eta_[k]));
    // (No draw where nothing can be reflected: with n = 1 the facet is, stream for stream, a
    // Lambertian one.)
    if (specular > 0 && rng.uniform() < specular) { // the interface reflects [M18 Eq. 6]
        wo = 2 * ci * m - wi;
        for (int k = 0; k < n; ++k) weight[k] *= f[k] / specular;
        return true;
    }
    // The body: leave with density T_0(o) cos / (pi (1 - r_e,0)) (cosine, accepted with T_0).
    double t0 = 1;
    do {
        wo = cosine_direction(m, rng);
        t0 = 1 - fresnel_dielectric(std::max(0.0, dot(wo, m)), eta_[0]);
    } while (t0 < 1 && rng.uniform() >= t0);
    const double co = std::max(0.0, dot(wo, m));
    bool alive = false;
    for (int k = 0; k < n; ++k) {
        // pi f_b / (P(body) x the exit density / (cos / pi)) [M18 Eq. 9].
        const double tk_i = 1 - f[k], tk_o = 1 - fresnel_dielectric(co, eta_[k]);
        const double body = tk_i * tk_o * kd_[k] / (eta_[k] * eta_[k] * (1 - kd_[k] * ri_[k]));
        weight[k] *= body / ((1 - specular) * t0 / (1 - re_[0]));
        alive = alive || weight[k] > 0;
    }
    return alive;
}

} // namespace gonio

namespace gonio {
namespace {
const Key kEta = Key::numbers("eta", {1, 100}, "interface index n_i (one or per wavelength)")
                     .cited("M18 section 3.1");
const Key kAlbedo = Key::numbers("albedo", {0, 1}, "substrate albedo K_d (one or per wavelength)")
                        .cited("M18 Eq. 9");
} // namespace
const MaterialKind& interfaced_lambertian_kind() {
    static const MaterialKind k{
        "interfaced_lambertian",
        "a Fresnel interface over a Lambertian substrate [M18 section 3.1]",
        {kAlbedo, kEta},
        [](TableReader& r, TableReader& spectrum) {
            FacetSpec s;
            s.type = "interfaced_lambertian";
            s.diffuse = true;
            s.albedo = read_per_channel(r, kAlbedo, spectrum, s.wavelengths_nm);
            s.interface_eta = read_per_channel(r, kEta, spectrum, s.wavelengths_nm);
            s.channels = int(std::max(s.albedo.size(), s.interface_eta.size()));
            s.description = "interfaced_lambertian(eta=" + list_text(s.interface_eta) +
                            "; albedo=" + list_text(s.albedo) + ")";
            const std::vector<double> eta = s.interface_eta, albedo = s.albedo;
            s.parts = [eta, albedo] {
                std::vector<std::unique_ptr<Material>> parts;
                parts.push_back(std::make_unique<InterfacedLambertianFacet>(eta, albedo));
                return parts;
            };
            return s;
        }};
    return k;
}
} // namespace gonio
