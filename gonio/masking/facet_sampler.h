#pragma once
// Points drawn uniformly by area on the triangulated facets of a height field (heightfield.h's
// split), with their facet's normal: a point's normal then follows the surface's own facet NDF
// D_s(m) dm. gonio masking and the decomposition models draw their points here.
#include "core/random.h"
#include "heightfield/heightfield.h"

#include <vector>

namespace gonio {

class FacetSampler {
  public:
    explicit FacetSampler(const HeightField& surface);
    // A_micro / A_macro: the facets' area over the patch's.
    double area_ratio() const { return area_ratio_; }
    void draw(Rng& rng, Vec3& position, Vec3& normal) const;

  private:
    const HeightField& surface_;
    std::vector<double> cdf_; // triangles by area (both of a cell project to half a cell)
    double area_ratio_ = 0;
};

} // namespace gonio
