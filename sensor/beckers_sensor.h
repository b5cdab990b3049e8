#pragma once
// Equal-area partition of the hemisphere into N cells (Beckers & Beckers 2012, "A general rule for
// disk and hemisphere partition into equal-area cells", Comput. Geom. 45(7)), as used by the
// virtual gonioreflectometer of R19 section 5. Every cell subtends exactly 2 pi / N sr.
//
// Rings are built from the rim inwards (docs/architecture.md): with S_0 = N cells inside
// the cap of angle pi/2, step inwards by d_theta = sqrt(2 pi / N) (the side of a square cell),
// round the number of cells inside the new cap, S_l = round(N (1 - cos theta_l)), and put the
// boundary exactly where that cap holds S_l cells: cos theta_l = 1 - S_l / N. A cap of fewer than 7
// cells becomes one polar cell. Since the number of cells inside the cap of angle theta is u = N (1
// - cos theta), a direction's ring is found from u through a bucket table; its cell in the ring
// from a fast azimuth estimate, decided by exact side tests against the cells' boundary directions
// when it lies near one: no trigonometry, no search.
//
// The transmission sensor below the surface is the mirror image of this one through the plane
// z = 0: cell c of the lower sensor holds the directions whose mirror image lies in cell c.
#include "core/math.h"

#include <vector>

namespace gonio {

struct SensorCell {
    int ring = 0;
    double theta_min = 0, theta_max = 0;     // radians, from the sensor's pole (+z, or -z below)
    double phi_min = 0, phi_max = 0;         // radians, in [0, 2 pi]
    double theta_center = 0, phi_center = 0; // the cell's equal-area midpoint
    Vec3 center;                      // unit direction of (theta_center, phi_center), upper side
    double solid_angle = 0;           // sr; 2 pi / N up to round-off
    double projected_solid_angle = 0; // sr; integral of cos(theta) over the cell
};

class BeckersSensor {
  public:
    // cells >= 1.
    explicit BeckersSensor(int cells);

    int cell_count() const { return n_; }
    int ring_count() const { return static_cast<int>(ring_first_.size()) - 1; }
    int ring_first_cell(int ring) const { return ring_first_[ring]; }
    int ring_cell_count(int ring) const { return ring_first_[ring + 1] - ring_first_[ring]; }
    const SensorCell& cell(int c) const { return cells_[c]; }
    // Every cell's projected solid angle, in cell order.
    std::vector<double> projected_solid_angles() const {
        std::vector<double> a;
        for (const SensorCell& c : cells_) a.push_back(c.projected_solid_angle);
        return a;
    }
    const std::vector<SensorCell>& cells() const { return cells_; }

    // Cell of a direction of the upper hemisphere (d.z >= 0; need not be exactly unit length in
    // phi, but d.z must be the cosine of its polar angle). Directions with d.z < 0 are clamped to
    // the horizon ring. phi = 2 pi wraps to 0.
    int lookup(const Vec3& d) const;
    // Cell of a direction of the lower hemisphere on the mirrored (transmission) sensor.
    int lookup_lower(const Vec3& d) const { return lookup({d.x, d.y, -d.z}); }

    // Ratio of a ring's polar extent to the azimuthal width of its cells at the mid polar angle:
    // 1 for square cells.
    double ring_aspect_ratio(int ring) const;

  private:
    int n_;
    std::vector<int> ring_first_;  // ring r holds cells [ring_first_[r], ring_first_[r+1]);
                                   // ring_first_[r] is also the cells inside the cap of ring r
    std::vector<double> ring_cos_; // cos of the outer boundary of cap r: 1 - ring_first_[r] / N
    std::vector<SensorCell> cells_;
    std::vector<int> ring_of_bucket_; // ring holding u = b N / buckets, for b < buckets
    double bucket_scale_ = 0;         // buckets / N
    std::vector<double> ring_scale_;  // per ring: cells / (2 pi)
    std::vector<double> boundary_;    // per cell: cos and sin of phi_min
};

// Cell energies stored [...][cell][channel] over each cell's projected solid angle: the cells'
// average BRDF, in 1/sr (the same for a cell of the upper sensor and its mirror image).
inline std::vector<double> cell_brdf(std::vector<double> energy,
                                     const std::vector<double>& projected_solid_angle,
                                     size_t channels) {
    const size_t cells = projected_solid_angle.size();
    for (size_t k = 0; k < energy.size(); ++k)
        energy[k] /= projected_solid_angle[(k / channels) % cells];
    return energy;
}

} // namespace gonio
