#include "gonio/model/microfacet_model.h"

#include "gonio/model/model_kind.h"

namespace gonio {

void MicrofacetModel::eval_cosine(const Vec3& i, const Vec3& o, double* out) const {
    const int nc = channels();
    Vec3 h;
    if (!reflection_half_vector(i, o, h)) {
        for (int c = 0; c < nc; ++c) out[c] = 0.0;
        return;
    }
    // R19 Eq. 2 times cos(theta_o): F D G2 / (4 |i.n|).
    const double geometric = ndf_.D(h) * ndf_.G2(i, o, h, masking_) / (4.0 * i.z);
    fresnel_.eval(dot(i, h), out);
    for (int c = 0; c < nc; ++c) out[c] *= geometric;
}

} // namespace gonio

namespace gonio {
// Held against simulated L1. A specular model: refused for diffuse facets.
const ModelKind& l1_model_kind() {
    static const ModelKind k{
        "l1",
        "Model L1: the specular microfacet BRDF with Smith masking [R19 Eq. 2]",
        {},
        [](TableReader& r, const ModelContext& c) {
            if (c.facets.diffuse)
                r.fail("models", "\"l1\" is a specular model; for " + c.facets.type +
                                     " facets use \"il\" (and \"vcavity\")");
            ModelChoice m;
            m.name = "l1";
            m.compared_with = "l1";
            m.description = "Model L1: the specular microfacet BRDF [R19 Eq. 2], masking " +
                            std::string(masking_name(c.masking));
            m.build = [ndf = c.ndf, fresnel = c.facets.fresnel,
                       masking = c.masking](const HeightField*) -> std::unique_ptr<BrdfModel> {
                return std::make_unique<MicrofacetModel>(*ndf, fresnel, masking);
            };
            return m;
        }};
    return k;
}
} // namespace gonio
