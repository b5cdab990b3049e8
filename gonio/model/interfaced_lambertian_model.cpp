#include "gonio/model/interfaced_lambertian_model.h"

#include "core/quadrature.h"
#include "gonio/model/model_kind.h"

#include <algorithm>
#include <cmath>

namespace gonio {

InterfacedLambertianModel::InterfacedLambertianModel(const Ndf& ndf, std::vector<double> eta,
                                                     std::vector<double> albedo,
                                                     MaskingForm masking, int body_points)
    : ndf_(ndf), facet_(std::move(eta), std::move(albedo)),
      specular_(ndf, FresnelTerm::dielectric(facet_.eta()), masking), masking_(masking) {
    const GaussLegendre& rule = gauss_legendre(body_points);
    if (ndf.continuous_sampler()) {
        // Nodes in the sampler's primary space: m = sample_m(u1, u2) has pdf D(m) m.n, so the
        // weights are the rule's over (m.n) and the nodes follow D however narrow it is.
        for (size_t a = 0; a < rule.nodes.size(); ++a)
            for (size_t b = 0; b < rule.nodes.size(); ++b) {
                const Vec3 m = ndf.sample_m(0.5 * (1 + rule.nodes[a]), 0.5 * (1 + rule.nodes[b]));
                if (m.z <= 0) continue;
                nodes_.push_back(m);
                weights_.push_back(0.25 * rule.weights[a] * rule.weights[b] / m.z);
            }
    } else {
        // A sampler that picks parts or rejects is not a smooth map (a table's body integral was
        // 4-6 % off that way): composite Gauss-Legendre in theta, on pieces doubling from the
        // narrowest feature, times 4 * body_points uniform azimuths, weighted by D sin(theta).
        const GaussLegendre& piece = gauss_legendre(8);
        std::vector<double> breaks{0.0};
        for (double t = ndf.narrowest_feature(); t < kPi / 2; t *= 2) breaks.push_back(t);
        breaks.push_back(kPi / 2);
        const int nphi = 4 * body_points;
        for (size_t k = 0; k + 1 < breaks.size(); ++k) {
            const double h = 0.5 * (breaks[k + 1] - breaks[k]),
                         c = 0.5 * (breaks[k + 1] + breaks[k]);
            for (size_t a = 0; a < piece.nodes.size(); ++a) {
                const double theta = c + h * piece.nodes[a];
                for (int j = 0; j < nphi; ++j) {
                    const Vec3 m = spherical_direction(theta, kTwoPi * (j + 0.5) / nphi);
                    const double d = ndf.D(m);
                    if (!(d > 0)) continue;
                    nodes_.push_back(m);
                    weights_.push_back(h * piece.weights[a] * std::sin(theta) * kTwoPi / nphi * d);
                }
            }
        }
    }
}

void InterfacedLambertianModel::specular_cosine(const Vec3& i, const Vec3& o, double* out) const {
    specular_.eval_cosine(i, o, out); // M18 Eq. 4 with Eq. 8
}

void InterfacedLambertianModel::body_cosine(const Vec3& i, const Vec3& o, double* out) const {
    const int nc = channels();
    for (int c = 0; c < nc; ++c) out[c] = 0.0;
    if (i.z <= 0 || o.z <= 0) return;
    // Smith's G depends on m only through the facet's visibility: computed once.
    double smith = 0;
    if (masking_ != MaskingForm::v_cavity) {
        const double li = ndf_.lambda(i), lo = ndf_.lambda(o);
        if (std::isinf(li) || std::isinf(lo)) return;
        smith = smith_g2(li, lo, i, o, masking_); // R19 Eq. 3, 9; Heitz 2014 Eq. 101
    }
    for (size_t n = 0; n < nodes_.size(); ++n) {
        const Vec3& m = nodes_[n];
        const double im = dot(i, m), om = dot(o, m);
        if (im <= 0 || om <= 0) continue;
        const double g = masking_ == MaskingForm::v_cavity ? ndf_.G2(i, o, m, masking_) : smith;
        // M18 Eq. 13 times o.n: f_b^mu G |i.m||o.m| / |i.n|, weighted by D dm.
        const double w = weights_[n] * g * im * om / i.z;
        for (int c = 0; c < nc; ++c) out[c] += w * facet_.body_brdf(i, o, m, c);
    }
}

void InterfacedLambertianModel::eval_cosine(const Vec3& i, const Vec3& o, double* out) const {
    const int nc = channels();
    double body[16];
    std::vector<double> heap;
    double* b = body;
    if (nc > 16) {
        heap.resize(size_t(nc));
        b = heap.data();
    }
    specular_cosine(i, o, out); // M18 Eq. 12: f = f_s + f_b
    body_cosine(i, o, b);
    for (int c = 0; c < nc; ++c) out[c] += b[c];
}

} // namespace gonio

namespace gonio {
namespace {
const Key kBodyPoints =
    Key::integer("body_points", {4, 256},
                 "il: Gauss-Legendre nodes per axis of the body integral over m")
        .fallback(32.0)
        .cited("M18 Eq. 13");
}
const ModelKind& il_model_kind() {
    static const ModelKind k{
        "il",
        "interfaced Lambertian microfacets, single scattering f_s + f_b [M18 Eq. 12-13]",
        {kBodyPoints},
        [](TableReader& r, const ModelContext& c) {
            if (!c.facets.diffuse)
                r.fail("models", "\"il\" needs lambertian or interfaced_lambertian facets, not " +
                                     c.facets.type);
            const int body_points = static_cast<int>(r.integer(kBodyPoints));
            ModelChoice m;
            m.name = "il";
            m.compared_with = ModelTarget::l1;
            m.description = "interfaced Lambertian microfacets, single scattering f_s + f_b "
                            "[M18 Eq. 12-13], masking " +
                            std::string(name_of(c.masking));
            m.build = integrated(c,
                                 [ndf = c.ndf, eta = c.facets.interface_eta,
                                  albedo = c.facets.albedo, masking = c.masking,
                                  body_points](const HeightField*) -> std::unique_ptr<BrdfModel> {
                                     return std::make_unique<InterfacedLambertianModel>(
                                         *ndf, eta, albedo, masking, body_points);
                                 });
            return m;
        }};
    return k;
}
} // namespace gonio
