#pragma once
// The traced surface: a backend (trace_backend.h: Embree, or gonio's own height-field traversal)
// behind one trace() that follows a ray across the periodic patch, the box [0, L]^2 x [zmin,
// zmax]: a segment that hits nothing leaves the box through the wall it meets first (no geometry
// lies beyond the walls, so any hit is inside); through a side wall it re-enters through the
// opposite one, and it leaves for good only through the top (or the bottom) plane. Scene itself
// does what every backend needs the same way: the box, and the ray origins kept on their side of
// the surface.
#include "core/math.h"
#include "gonio/trace/trace_backend.h"
#include "heightfield/heightfield.h"

#include <cstddef>
#include <memory>
#include <vector>

namespace gonio {

class Scene {
  public:
    explicit Scene(const HeightField& surface,
                   const TraceBackendKind& backend = default_trace_backend());
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    double period() const { return box_.period; } // L = n * spacing
    int cells() const { return n_; }              // n, per side
    double spacing() const { return box_.period / n_; }
    double z_min() const { return box_.z_min; }
    double z_max() const { return box_.z_max; }
    // Scale of the coordinates, for offsetting ray origins off the surface.
    double epsilon() const { return box_.epsilon; }

    static constexpr int kMaxWraps = 1 << 20; // side walls a ray may cross by default

    // Follows the ray from `origin` (inside the box or on its top plane) along unit `dir` to the
    // first facet it hits, wrapping through the side walls, or to where it leaves the box.
    // `below`: the ray travels under the surface (inside a transmissive material), so it meets
    // facets from below and leaves through the bottom plane. max_wraps bounds near-horizontal
    // rays (kind = lost when exceeded).
    // `beam` (from beam_entry): a ray of the beam starts its walk where its origin's block is
    // clear of the surface (the same hit, fewer steps; backends without it ignore it).
    SurfaceHit trace(Vec3 origin, const Vec3& dir, bool below = false, int max_wraps = kMaxWraps,
                     const BeamEntry* beam = nullptr) const;

    // trace() of each of n rays, hits[i] for rays[i] (whose origins it may repair): the backend
    // may trace them side by side.
    void trace_stream(StreamRay* rays, std::size_t n, int max_wraps, SurfaceHit* hits) const;

    // For a beam of `rays` rays of unit direction dir (going down) from the top plane,
    // z_max() + epsilon(): what trace() needs to start them lower (empty where the backend has
    // nothing to gain).
    BeamEntry beam_entry(const Vec3& dir, long long rays) const {
        return backend_->beam_entry(dir, box_.z_max + box_.epsilon, rays);
    }

    const TraceBackendKind& backend() const { return kind_; }
    // What the acceleration structure holds (Embree's allocations, the traversal's tables).
    std::size_t memory_bytes() const { return backend_->memory_bytes(); }

    // One segment as the backend sees it, with no wrapping (for the benchmark and the tests).
    SegmentHit intersect(const float origin[3], const float dir[3]) const {
        return backend_->intersect(origin, dir);
    }
    // n segments [n][origin, dir] at once, their first hits' t, through the backend's packets.
    void intersect_packets(const float* segments, std::size_t n, double* t) const {
        backend_->intersect_packets(segments, n, t);
    }
    // Vertex (i, j) of the triangulated surface, i, j in [0, n], as the backend holds it.
    Vec3 vertex(int i, int j) const { return backend_->vertex(i, j); }

    // For the benchmark: while set (single-threaded use only), every ray the backend gives its
    // library (Embree) is appended to *sink as origin x, y, z and direction x, y, z.
    void record_segments(std::vector<float>* sink) { backend_->record_segments(sink); }

  private:
    const TraceBackendKind& kind_;
    SceneBox box_;
    int n_ = 0;
    double border_lo_ = 0, border_hi_ = 0; // the patch's inside, in float, nearest the border
    std::unique_ptr<TraceBackend> backend_;

    // Moves the origin o of a ray along d onto its side of the surface as the backend sees it
    // (r.lifted when it did).
    void repair(Vec3& o, const Vec3& d, bool below, SurfaceHit& r) const;
};

} // namespace gonio
