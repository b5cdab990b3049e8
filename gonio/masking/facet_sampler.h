#pragma once
// Points drawn uniformly by area on the triangulated facets of a height field (heightfield.h's
// split), with their facet's normal: a point's normal then follows the surface's own facet NDF
// D_s(m) dm. gonio masking and the decomposition models draw their points here.
#include "core/random.h"
#include "heightfield/heightfield.h"

#include <vector>

namespace gonio {

// The table of the surface's facet NDF D_s that gonio masking and the decomposition models take
// Smith's Lambda_s from: 1 degree by 5 (the height_map family's default is 2 by 10).
struct FacetTable {
    int theta_intervals = 90, phi_count = 72;
};
inline constexpr FacetTable kFacetTable{};

class FacetSampler {
  public:
    explicit FacetSampler(const HeightField& surface); // keeps a reference to it
    FacetSampler(const FacetSampler&) = delete;
    FacetSampler& operator=(const FacetSampler&) = delete;
    // A_micro / A_macro: the facets' area over the patch's.
    double area_ratio() const { return area_ratio_; }
    void draw(Rng& rng, Vec3& position, Vec3& normal) const;

  private:
    const HeightField& surface_;
    std::vector<double> cdf_; // triangles by area (both of a cell project to half a cell)
    double area_ratio_ = 0;
};

} // namespace gonio
