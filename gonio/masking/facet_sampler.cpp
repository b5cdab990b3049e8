#include "gonio/masking/facet_sampler.h"

#include <algorithm>
#include <cmath>

namespace gonio {

FacetSampler::FacetSampler(const HeightField& s) : surface_(s) {
    const int n = s.n;
    cdf_.resize(size_t(2) * n * n);
    double total = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            for (int t = 0; t < 2; ++t) {
                double p, q;
                s.triangle_slopes(x, y, t, p, q);
                total += std::sqrt(1.0 + p * p + q * q); // area = projected area / m.z
                cdf_[(size_t(y) * n + x) * 2 + t] = total;
            }
    area_ratio_ = total / (2.0 * n * n); // each triangle projects to half a cell
    for (double& c : cdf_) c /= total;
}

void FacetSampler::draw(Rng& rng, Vec3& position, Vec3& normal) const {
    const size_t k =
        size_t(std::lower_bound(cdf_.begin(), cdf_.end(), rng.uniform()) - cdf_.begin());
    const size_t tri = std::min(k, cdf_.size() - 1);
    const int n = surface_.n, t = int(tri % 2), cell = int(tri / 2), x = cell % n, y = cell / n;
    double u = rng.uniform(), v = rng.uniform();
    if (u + v > 1) u = 1 - u, v = 1 - v; // uniform in the triangle (planar: uniform on the facet)
    // Triangle A: (x, y), (x+1, y), (x, y+1); B: (x+1, y+1), (x, y+1), (x+1, y) (heightfield.h).
    const double gx = t == 0 ? x + u : x + 1 - u, gy = t == 0 ? y + v : y + 1 - v;
    double p, q;
    surface_.triangle_slopes(x, y, t, p, q);
    position = {gx * surface_.spacing, gy * surface_.spacing, surface_.height_at_grid(gx, gy)};
    normal = HeightField::normal_of_slopes(p, q);
}

} // namespace gonio
