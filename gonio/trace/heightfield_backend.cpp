// The height-field backend: HeightfieldTraversal (heightfield_traversal.h), a walk over the same
// triangles as Embree's grid (the same split and float vertices) made for a periodic grid: a
// min-max pyramid, native wrapping, no BVH.
#include "gonio/trace/trace_backend.h"

#include <limits>

namespace gonio {

namespace {
class HeightfieldBackend final : public TraceBackend {
  public:
    HeightfieldBackend(const HeightField& s, const SceneBox& box) : box_(box), walk_(s) {}

    void trace(Vec3 o, const Vec3& d, double side, int max_wraps, const BeamEntry* beam,
               SurfaceHit& r) const override {
        for (;;) {
            const TraversalHit h =
                walk_.trace(o, d, box_.z_max + box_.epsilon, box_.z_min - box_.epsilon,
                            max_wraps - r.wraps, beam);
            r.wraps += h.wraps;
            if (h.kind == TraversalHit::escaped_up || h.kind == TraversalHit::escaped_down) {
                r.kind = h.kind == TraversalHit::escaped_up ? SurfaceHit::escaped_up
                                                            : SurfaceHit::escaped_down;
                return;
            }
            if (h.kind != TraversalHit::hit) {
                r.kind = SurfaceHit::lost;
                return;
            }
            const Vec3 up = normalize(h.normal);
            if (side * dot(d, up) > 0) { // met from the wrong side: as the Embree backend does
                o = h.position + side * box_.epsilon * up;
                if (++r.reentries > 64) {
                    r.kind = SurfaceHit::lost;
                    return;
                }
                continue;
            }
            r.kind = SurfaceHit::hit;
            r.normal = up;
            r.position = h.position;
            return;
        }
    }

    SegmentHit intersect(const float o[3], const float d[3]) const override {
        SegmentHit h;
        const Vec3 origin{o[0], o[1], o[2]}, dir{d[0], d[1], d[2]};
        const TraversalHit t =
            walk_.trace(origin, dir, box_.z_max + box_.epsilon, box_.z_min - box_.epsilon, 0);
        if (t.kind != TraversalHit::hit) {
            h.t = std::numeric_limits<double>::infinity();
            return h;
        }
        h.t = t.t, h.point = origin + t.t * dir;
        h.cell_x = t.cell_x, h.cell_y = t.cell_y, h.triangle = t.triangle;
        return h;
    }
    Vec3 vertex(int i, int j) const override { return walk_.vertex(i, j); }
    double height_at(double x, double y) const override { return walk_.height_at(x, y); }
    bool float_origins() const override { return false; }
    BeamEntry beam_entry(const Vec3& d, double z_start, long long rays) const override {
        return walk_.beam_entry(d, z_start, rays);
    }
    std::size_t memory_bytes() const override { return walk_.memory_bytes(); }

  private:
    SceneBox box_;
    HeightfieldTraversal walk_;
};
} // namespace

const TraceBackendKind& heightfield_backend() {
    static const TraceBackendKind k{
        "heightfield", "gonio's own walk over the periodic grid: min-max pyramid, native wrapping",
        [](const HeightField& s, const SceneBox& box) -> std::unique_ptr<TraceBackend> {
            return std::make_unique<HeightfieldBackend>(s, box);
        }};
    return k;
}

} // namespace gonio
