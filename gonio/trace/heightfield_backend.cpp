// The height-field backend: HeightfieldTraversal (heightfield_traversal.h), a walk over the same
// triangles as Embree's grid (the same split and float vertices) made for a periodic grid: a
// min-max pyramid, native wrapping, no BVH.
#include "gonio/trace/trace_backend.h"

#include <limits>
#include <vector>

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
            Vec3 up;
            if (!complete(h, d, side, r, up)) return;
            // Met from the wrong side: as the Embree backend does.
            o = h.position + side * box_.epsilon * up;
            if (++r.reentries > 64) {
                r.kind = SurfaceHit::lost;
                return;
            }
        }
    }

    // The stream's rays side by side (HeightfieldTraversal::trace_lanes); what trace() does after
    // the walk, per ray; a ray that met a facet from the wrong side is traced again by trace().
    void trace_stream(const StreamRay* rays, std::size_t n, int max_wraps,
                      SurfaceHit* hits) const override {
        std::vector<LaneRay>& in = lane_rays();
        std::vector<TraversalHit>& out = lane_hits();
        in.resize(n), out.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            in[i] = LaneRay{rays[i].origin, rays[i].dir, max_wraps, rays[i].beam};
        walk_.trace_lanes(in.data(), n, box_.z_max + box_.epsilon, box_.z_min - box_.epsilon,
                          out.data());
        for (std::size_t i = 0; i < n; ++i) {
            const double side = rays[i].below ? -1.0 : 1.0;
            Vec3 up;
            if (complete(out[i], rays[i].dir, side, hits[i], up)) { // rare: trace()'s re-entries
                hits[i].wraps = 0;
                trace(rays[i].origin, rays[i].dir, side, max_wraps, rays[i].beam, hits[i]);
            }
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
    // Completes r from the walk's result h (its walls added to r's) for a ray along d on `side`,
    // but for a facet met from the wrong side: true then, its unit normal in up.
    static bool complete(const TraversalHit& h, const Vec3& d, double side, SurfaceHit& r,
                         Vec3& up) {
        r.wraps += h.wraps;
        if (h.kind == TraversalHit::escaped_up || h.kind == TraversalHit::escaped_down) {
            r.kind = h.kind == TraversalHit::escaped_up ? SurfaceHit::escaped_up
                                                        : SurfaceHit::escaped_down;
            return false;
        }
        if (h.kind != TraversalHit::hit) {
            r.kind = SurfaceHit::lost;
            return false;
        }
        up = normalize(h.normal);
        if (side * dot(d, up) > 0) return true;
        r.kind = SurfaceHit::hit;
        r.normal = up;
        r.position = h.position;
        return false;
    }
    // Per thread, the stream's rays and hits as the traversal takes them (kept between calls).
    static std::vector<LaneRay>& lane_rays() {
        thread_local std::vector<LaneRay> v;
        return v;
    }
    static std::vector<TraversalHit>& lane_hits() {
        thread_local std::vector<TraversalHit> v;
        return v;
    }
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
