#include "gonio/model/microfacet_model.h"

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
