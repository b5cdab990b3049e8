#pragma once
// What traces rays against the patch for Scene (scene.h): a backend holds the triangulated height
// field (Embree's grid split: each cell's (v0, v1, v3) and (v2, v3, v1), float vertices) and
// follows a ray, wrapping through the side walls, to its first facet or out through the top or
// bottom plane. Scene keeps what every backend shares (the box, the origin repair near sharp
// edges) in one place. Each backend lives in its own file and is listed once in trace_backends();
// `trace.backend`, `gonio info` and the benchmark take their names from there.
#include "core/math.h"
#include "gonio/trace/heightfield_traversal.h"
#include "heightfield/heightfield.h"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace gonio {

// One segment's first hit, for comparing backends: t (infinity: none), the point o + t d in the
// patch, and the triangle (cell and 0 / 1 as heightfield.h names them).
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
    bool lifted = false; // the origin, as the backend sees it, lay on the wrong side
};

// One ray of a stream (Scene::trace_stream): its origin, unit direction, whether it travels under
// the surface, and the beam it belongs to (nullptr for any other ray).
struct StreamRay {
    Vec3 origin, dir;
    bool below = false;
    const BeamEntry* beam = nullptr;
};

// The box the patch fills, [0, L]^2 x [z_min, z_max], and the offset that leaves a facet.
struct SceneBox {
    double period = 0, z_min = 0, z_max = 0, epsilon = 0;
};

class TraceBackend {
  public:
    virtual ~TraceBackend() = default;
    // Completes r for the ray from `origin` along unit `dir` (Scene has repaired the origin):
    // side +1 above the surface, -1 below (a ray inside a transmissive material); at most
    // max_wraps side walls, else kind = lost; `beam` as Scene::trace says.
    virtual void trace(Vec3 origin, const Vec3& dir, double side, int max_wraps,
                       const BeamEntry* beam, SurfaceHit& r) const = 0;
    // Completes hits[i] for each of n rays (origins repaired by Scene) as trace() would: by
    // default one by one; a backend may trace them side by side, with the same hits.
    virtual void trace_stream(const StreamRay* rays, std::size_t n, int max_wraps,
                              SurfaceHit* hits) const {
        for (std::size_t i = 0; i < n; ++i)
            trace(rays[i].origin, rays[i].dir, rays[i].below ? -1.0 : 1.0, max_wraps, rays[i].beam,
                  hits[i]);
    }
    // One segment, no wrapping: the first triangle at t >= 0 from either side in the patch.
    virtual SegmentHit intersect(const float origin[3], const float dir[3]) const = 0;
    // For the benchmark: the first hits' t (infinity: none) of n segments [n][origin, dir], as
    // intersect() finds them, through the widest ray packets the library has (Embree's
    // rtcIntersect8); one by one by default.
    virtual void intersect_packets(const float* segments, std::size_t n, double* t) const {
        for (std::size_t i = 0; i < n; ++i)
            t[i] = intersect(segments + 6 * i, segments + 6 * i + 3).t;
    }
    // Vertex (i, j), i, j in [0, n], and the triangulated height at (x, y), as the backend holds
    // the surface.
    virtual Vec3 vertex(int i, int j) const = 0;
    virtual double height_at(double x, double y) const = 0;
    // The backend sees ray origins in float (Embree), not in double.
    virtual bool float_origins() const = 0;
    // What a beam's rays need to start lower (beam_entry of heightfield_traversal.h); none by
    // default.
    virtual BeamEntry beam_entry(const Vec3&, double, long long) const { return {}; }
    // What the acceleration structure holds.
    virtual std::size_t memory_bytes() const = 0;
    // For the benchmark: the rays given to the underlying library, if the backend can record
    // them (single-threaded use only).
    virtual void record_segments(std::vector<float>*) {}
};

struct TraceBackendKind {
    const char* name;
    const char* summary;
    std::unique_ptr<TraceBackend> (*create)(const HeightField& surface, const SceneBox& box);
};

const std::vector<const TraceBackendKind*>& trace_backends();
// Throws std::invalid_argument naming the backends.
const TraceBackendKind& trace_backend_named(const std::string& name);
const TraceBackendKind& default_trace_backend();
const TraceBackendKind& embree_backend();
const TraceBackendKind& heightfield_backend();

} // namespace gonio
