#include "gonio/material/material.h"

#include <vector>

namespace gonio {

bool SpecularReflector::scatter(const Vec3& wi, const Vec3& m, Rng&, Vec3& wo,
                                double* weight) const {
    const double c = dot(wi, m);
    wo = reflect(wi, m);
    if (fresnel_.kind() == FresnelTerm::Kind::mirror) return true; // F = 1
    double f[16];
    std::vector<double> many;
    double* F = f;
    if (channels() > 16) many.resize(channels()), F = many.data();
    fresnel_.eval(std::abs(c), F);
    for (int k = 0; k < channels(); ++k) weight[k] *= F[k];
    return true;
}

} // namespace gonio
