#pragma once
// A height field in Embree 3 as one grid geometry ((n+1)^2 vertices, the last row and column
// repeating the first, so the patch is periodic), with the ROBUST scene flag and an error
// callback. A grid is an order of magnitude smaller and faster to build than a triangle mesh.
// Embree splits every grid cell like a quad, into (v0, v1, v3) and (v2, v3, v1): the two
// triangles of heightfield.h.
//
// trace() follows a ray across the periodic patch, the box [0, L]^2 x [zmin, zmax]: a segment that
// hits nothing leaves the box through the wall it meets first (no geometry lies beyond the walls,
// so any hit is inside); through a side wall it re-enters through the opposite one, and it leaves
// for good only through the top (or the bottom) plane.
#include "core/math.h"
#include "heightfield/heightfield.h"

#include <embree3/rtcore.h>
#include <string>
#include <vector>

namespace gonio {

struct SurfaceHit {
    enum Kind { hit, escaped_up, escaped_down, lost } kind = lost;
    Vec3 position;       // on the surface, in the patch [0, L)^2 (hit only)
    Vec3 normal;         // the facet's unit normal, facing +z (hit only)
    int wraps = 0;       // side walls crossed
    int reentries = 0;   // facets met from the wrong side and passed (rounding at sharp edges)
    bool lifted = false; // the origin, as Embree sees it in float, lay on the wrong side
};

class Scene {
  public:
    explicit Scene(const HeightField& surface);
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    double period() const { return period_; } // L = n * spacing
    double z_min() const { return z_min_; }
    double z_max() const { return z_max_; }
    // Scale of the coordinates, for offsetting ray origins off the surface.
    double epsilon() const { return epsilon_; }

    // Follows the ray from `origin` (inside the box or on its top plane) along unit `dir` to the
    // first facet it hits, wrapping through the side walls, or to where it leaves the box.
    // `below`: the ray travels under the surface (inside a transmissive material), so it meets
    // facets from below and leaves through the bottom plane. max_wraps bounds near-horizontal
    // rays (kind = lost when exceeded).
    SurfaceHit trace(Vec3 origin, const Vec3& dir, bool below = false,
                     int max_wraps = 1 << 20) const;

    // One bare rtcIntersect1 call (for the benchmark): the hit distance, or infinity.
    float intersect(const float origin[3], const float dir[3]) const;

    // For the benchmark: while set (single-threaded use only), every ray trace() gives Embree is
    // appended to *sink as origin x, y, z and direction x, y, z.
    void record_segments(std::vector<float>* sink) { recorder_ = sink; }

  private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    double period_ = 0, z_min_ = 0, z_max_ = 0, epsilon_ = 0;
    double inv_spacing_ = 1;               // for exact heights without a division
    double border_lo_ = 0, border_hi_ = 0; // the patch's inside, in float, nearest the border
    std::string error_;                    // first error reported by Embree's callback
    std::vector<float>* recorder_ = nullptr;
    // The vertices as Embree holds them ((n+1)^2, x y z floats): the exact triangulated surface,
    // to keep ray origins outside it, read where Embree has just read it (in cache).
    const float* vertices_ = nullptr;
    int n_ = 0;
};

} // namespace gonio
