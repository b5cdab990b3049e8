#include "gonio/model/microfacet_model.h"

#include "gonio/model/model_kind.h"

#include <atomic>
#include <cstring>

namespace gonio {

namespace {
// The cell integrator evaluates the BRDF at one incidence i for every o: Lambda(i) (for a table,
// an acos, an atan2 and a bicubic lookup) is the same each time. Each thread keeps the last one,
// keyed by the model's id (never reused, unlike an address) and i's exact bits.
struct LambdaCache {
    std::uint64_t owner = 0;
    double key[3] = {0, 0, 0};
    double value = 0;
};
thread_local LambdaCache lambda_cache;
} // namespace

std::uint64_t MicrofacetModel::next_id() {
    static std::atomic<std::uint64_t> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
}

double MicrofacetModel::lambda_i(const Vec3& i) const {
    LambdaCache& c = lambda_cache;
    const double key[3] = {i.x, i.y, i.z};
    if (c.owner != id_ || std::memcmp(c.key, key, sizeof key) != 0) {
        c.value = ndf_.lambda(i);
        c.owner = id_;
        std::memcpy(c.key, key, sizeof key);
    }
    return c.value;
}

void MicrofacetModel::eval_cosine(const Vec3& i, const Vec3& o, double* out) const {
    const int nc = channels();
    Vec3 h;
    if (!reflection_half_vector(i, o, h)) {
        for (int c = 0; c < nc; ++c) out[c] = 0.0;
        return;
    }
    // R19 Eq. 2 times cos(theta_o): F D G2 / (4 |i.n|). Where D(h) = 0 (outside a table's
    // support) the product is 0 whatever G2 in [0, 1] is: G2's two Lambdas are skipped.
    const double d = ndf_.D(h);
    if (d == 0) {
        for (int c = 0; c < nc; ++c) out[c] = 0.0;
        return;
    }
    const double g2 = masking_ == MaskingForm::v_cavity ? ndf_.G2(i, o, h, masking_)
                                                        : ndf_.G2(i, o, h, masking_, lambda_i(i));
    const double geometric = d * g2 / (4.0 * i.z);
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
            m.compared_with = ModelTarget::l1;
            m.description = "Model L1: the specular microfacet BRDF [R19 Eq. 2], masking " +
                            std::string(name_of(c.masking));
            m.build =
                integrated(c,
                           [ndf = c.ndf, fresnel = c.facets.fresnel,
                            masking = c.masking](const HeightField*) -> std::unique_ptr<BrdfModel> {
                               return std::make_unique<MicrofacetModel>(*ndf, fresnel, masking);
                           });
            return m;
        }};
    return k;
}
} // namespace gonio
