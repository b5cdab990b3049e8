#pragma once
// The traced surface, with one of two backends behind one trace():
// - embree: the height field in Embree 3 as one grid geometry ((n+1)^2 vertices, the last row and
// column repeating the first, so the patch is periodic), with the ROBUST scene flag and an error
// callback. A grid is an order of magnitude smaller and faster to build than a triangle mesh.
// Embree splits every grid cell like a quad, into (v0, v1, v3) and (v2, v3, v1): the two
// triangles of heightfield.h.
//
// - heightfield: HeightfieldTraversal, a walk over the same triangles (the same split and float
//   vertices) made for a periodic grid: a min-max pyramid, native wrapping, no BVH.
//
// trace() follows a ray across the periodic patch, the box [0, L]^2 x [zmin, zmax]: a segment that
// hits nothing leaves the box through the wall it meets first (no geometry lies beyond the walls,
// so any hit is inside); through a side wall it re-enters through the opposite one, and it leaves
// for good only through the top (or the bottom) plane.
#include "core/math.h"
#include "gonio/trace/heightfield_traversal.h"
#include "heightfield/heightfield.h"

#include <atomic>
#include <cstddef>
#include <embree3/rtcore.h>
#include <memory>
#include <string>
#include <vector>

namespace gonio {

enum class TraceBackend { embree, heightfield };
inline constexpr TraceBackend kDefaultTraceBackend = TraceBackend::embree;
const char* backend_name(TraceBackend b);
TraceBackend parse_backend(const std::string& name); // throws std::invalid_argument

// One segment's first hit, for comparing backends: t (infinity: none), the point o + t d in the
// patch, and the triangle (cell and 0 / 1 as heightfield.h names them; Embree's from the point).
struct SegmentHit {
    double t = 0;
    Vec3 point;
    int cell_x = -1, cell_y = -1, triangle = -1;
};

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
    explicit Scene(const HeightField& surface, TraceBackend backend = kDefaultTraceBackend);
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    double period() const { return period_; } // L = n * spacing
    int cells() const { return n_; }          // n, per side
    double spacing() const { return period_ / n_; }
    double z_min() const { return z_min_; }
    double z_max() const { return z_max_; }
    // Scale of the coordinates, for offsetting ray origins off the surface.
    double epsilon() const { return epsilon_; }

    static constexpr int kMaxWraps = 1 << 20; // side walls a ray may cross by default

    // Follows the ray from `origin` (inside the box or on its top plane) along unit `dir` to the
    // first facet it hits, wrapping through the side walls, or to where it leaves the box.
    // `below`: the ray travels under the surface (inside a transmissive material), so it meets
    // facets from below and leaves through the bottom plane. max_wraps bounds near-horizontal
    // rays (kind = lost when exceeded).
    // `beam` (from beam_entry): a ray of the beam starts its walk where its origin's block is
    // clear of the surface (the same hit, fewer steps; the Embree backend ignores it).
    SurfaceHit trace(Vec3 origin, const Vec3& dir, bool below = false, int max_wraps = kMaxWraps,
                     const BeamEntry* beam = nullptr) const;

    // For a beam of `rays` rays of unit direction dir (going down) from the top plane,
    // z_max() + epsilon(): what trace() needs to start them lower (empty for the Embree backend).
    BeamEntry beam_entry(const Vec3& dir, long long rays) const;

    TraceBackend backend() const { return backend_; }
    // What the acceleration structure holds: Embree's allocations (vertices, BVH) or the
    // traversal's heights and pyramid.
    std::size_t memory_bytes() const { return memory_bytes_; }

    // One segment as the backend sees it, with no wrapping (for the benchmark and the tests):
    // Embree's bare rtcIntersect1, or the traversal stopped at the patch's walls. The first
    // triangle at t >= 0 from either side; t = infinity when none in the patch.
    SegmentHit intersect(const float origin[3], const float dir[3]) const;

    // Vertex (i, j) of the triangulated surface, i, j in [0, n], as the backend holds it.
    Vec3 vertex(int i, int j) const;

    // For the benchmark: while set (single-threaded use only), every ray trace() gives Embree is
    // appended to *sink as origin x, y, z and direction x, y, z.
    void record_segments(std::vector<float>* sink) { recorder_ = sink; }

  private:
    // Complete r (which trace() began) for the backend; in place, not copied in and out.
    void trace_embree(Vec3 origin, const Vec3& dir, double side, int max_wraps,
                      SurfaceHit& r) const;
    void trace_heightfield(Vec3 origin, const Vec3& dir, double side, int max_wraps,
                           const BeamEntry* beam, SurfaceHit& r) const;

    TraceBackend backend_;
    std::size_t memory_bytes_ = 0;
    std::unique_ptr<HeightfieldTraversal> walk_; // heightfield backend
    RTCDevice device_ = nullptr;                 // embree backend
    RTCScene scene_ = nullptr;
    double period_ = 0, z_min_ = 0, z_max_ = 0, epsilon_ = 0;
    double inv_spacing_ = 1;                 // for exact heights without a division
    double border_lo_ = 0, border_hi_ = 0;   // the patch's inside, in float, nearest the border
    std::string error_;                      // first error reported by Embree's callback
    std::vector<float>* recorder_ = nullptr; // embree backend only
    std::atomic<long long> embree_bytes_{0}; // Embree's allocations, from its memory monitor
    // The vertices as Embree holds them ((n+1)^2, x y z floats): the exact triangulated surface,
    // to keep ray origins outside it, read where Embree has just read it (in cache).
    const float* vertices_ = nullptr;
    int n_ = 0;
};

} // namespace gonio
