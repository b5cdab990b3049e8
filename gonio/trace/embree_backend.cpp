// The Embree backend: the height field in Embree 3 as one grid geometry ((n+1)^2 vertices, the
// last row and column repeating the first, so the patch is periodic), with the ROBUST scene flag
// and an error callback. A grid is an order of magnitude smaller and faster to build than a
// triangle mesh. Embree splits every grid cell like a quad, into (v0, v1, v3) and (v2, v3, v1):
// the two triangles of heightfield.h. The reference backend: the height-field traversal is held
// against it hit for hit.
#include "gonio/trace/embree_device.h"
#include "gonio/trace/trace_backend.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <embree3/rtcore.h>
#include <limits>
#include <stdexcept>
#include <string>

namespace gonio {

namespace {
// A ray from o along d with no far limit, for rtcIntersect1.
RTCRayHit embree_ray(float ox, float oy, float oz, float dx, float dy, float dz) {
    RTCRayHit rh;
    rh.ray.org_x = ox, rh.ray.org_y = oy, rh.ray.org_z = oz;
    rh.ray.dir_x = dx, rh.ray.dir_y = dy, rh.ray.dir_z = dz;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0, rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

// Embree calls this from C code: record the first error (no exception may cross C frames);
// the constructor checks it after building.
void embree_error(void* user, RTCError code, const char* message) {
    auto* first = static_cast<std::string*>(user);
    if (first->empty())
        *first = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "?");
}

// Embree's allocations as they happen (it may allocate from several threads while building).
bool embree_memory(void* user, ssize_t bytes, bool) {
    static_cast<std::atomic<long long>*>(user)->fetch_add(bytes, std::memory_order_relaxed);
    return true;
}

class EmbreeBackend final : public TraceBackend {
  public:
    EmbreeBackend(const HeightField& s, const SceneBox& box)
        : box_(box), n_(s.n), inv_spacing_(1.0 / s.spacing) {
        const int v = n_ + 1;
        device_ = new_embree_device();
        if (!device_) throw std::runtime_error("Embree: cannot create a device");
        rtcSetDeviceErrorFunction(device_, embree_error, &error_);
        rtcSetDeviceMemoryMonitorFunction(device_, embree_memory, &bytes_);
        scene_ = rtcNewScene(device_);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_GRID);
        float* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), size_t(v) * v));
        for (int y = 0; y < v; ++y)
            for (int x = 0; x < v; ++x) {
                float* p = vertices + 3 * (size_t(y) * v + x);
                // s.at wraps: the last row and column repeat the first
                p[0] = float(x * s.spacing), p[1] = float(y * s.spacing), p[2] = s.at(x, y);
            }
        vertices_ = vertices; // owned by the geometry, which the scene keeps alive
        RTCGrid* grid = static_cast<RTCGrid*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, sizeof(RTCGrid), 1));
        grid->startVertexID = 0;
        grid->stride = unsigned(v);
        grid->width = static_cast<unsigned short>(v);
        grid->height = static_cast<unsigned short>(v);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene_, geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(scene_);
        if (!error_.empty()) {
            release();
            throw std::runtime_error(error_);
        }
    }
    ~EmbreeBackend() override { release(); }

    void trace(Vec3 o, const Vec3& d, double side, int max_wraps, const BeamEntry*,
               SurfaceHit& r) const override;
    SegmentHit intersect(const float o[3], const float d[3]) const override;
    void intersect_packets(const float* segments, std::size_t n, double* t) const override;
    Vec3 vertex(int i, int j) const override {
        const float* p = vertices_ + 3 * (size_t(j) * size_t(n_ + 1) + size_t(i));
        return {p[0], p[1], p[2]};
    }
    double height_at(double x, double y) const override {
        const int stride = n_ + 1;
        return HeightField::triangulated_height(
            x * inv_spacing_, y * inv_spacing_, n_, nullptr, nullptr,
            [&](int i, int j) { return vertices_[3 * (size_t(j) * stride + i) + 2]; });
    }
    bool float_origins() const override { return true; }
    std::size_t memory_bytes() const override { return size_t(std::max(0LL, bytes_.load())); }
    void record_segments(std::vector<float>* sink) override { recorder_ = sink; }

  private:
    // Embree sees the ray in float, the wall point o is in double: a ray that meets the surface
    // within that rounding of a side wall can reach the wall unhit and already past the surface,
    // and re-entered there it would pass under it for good (measured: GGX alpha 5, 32^2, one
    // beam ray in 4096 left through the bottom). The heights at the wall are the same on both
    // sides (the patch is periodic), so such a ray met the facet at the wall in the cell it
    // leaves: report that hit there, on the surface.
    bool crossed_before_wall(const Vec3& o, const Vec3& d, double side, bool wall_x, bool wall_y,
                             SurfaceHit& r) const {
        double gx = o.x * inv_spacing_, gy = o.y * inv_spacing_;
        // The cell being left: just inside the wall crossed (x = L lies in cell n - 1).
        if (wall_x) gx = d.x > 0 ? std::nextafter(double(n_), 0.0) : 0.0;
        if (wall_y) gy = d.y > 0 ? std::nextafter(double(n_), 0.0) : 0.0;
        const int stride = n_ + 1;
        double a, b;
        const double surface =
            HeightField::triangulated_height(gx, gy, n_, &a, &b, [&](int i, int j) {
                return vertices_[3 * (size_t(j) * stride + i) + 2];
            });
        if (side * (o.z - surface) >= 0) return false;
        r.kind = SurfaceHit::hit;
        r.normal = HeightField::normal_of_slopes(a * inv_spacing_, b * inv_spacing_);
        // In the patch [0, L)^2, as every hit: the wall at L is the wall at 0.
        r.position = {o.x >= box_.period ? 0.0 : o.x, o.y >= box_.period ? 0.0 : o.y, surface};
        return true;
    }

    void release() {
        if (scene_) rtcReleaseScene(scene_);
        if (device_) rtcReleaseDevice(device_);
        scene_ = nullptr, device_ = nullptr;
    }

    SceneBox box_;
    int n_;
    double inv_spacing_;
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::string error_;               // first error reported by Embree's callback
    std::atomic<long long> bytes_{0}; // Embree's allocations, from its memory monitor
    const float* vertices_ = nullptr; // (n+1)^2 x y z floats, as Embree holds them
    std::vector<float>* recorder_ = nullptr;
};

void EmbreeBackend::intersect_packets(const float* s, std::size_t n, double* t) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT; // neighbours in a packet: a beam's rays
    constexpr std::size_t W = 8;                         // AVX2's native packet (max_isa=avx2)
    for (std::size_t first = 0; first < n; first += W) {
        alignas(32) int valid[W];
        alignas(32) RTCRayHit8 rh;
        for (std::size_t k = 0; k < W; ++k) {
            const std::size_t i = std::min(first + k, n - 1);
            const float* o = s + 6 * i;
            valid[k] = first + k < n ? -1 : 0;
            rh.ray.org_x[k] = o[0], rh.ray.org_y[k] = o[1], rh.ray.org_z[k] = o[2];
            rh.ray.dir_x[k] = o[3], rh.ray.dir_y[k] = o[4], rh.ray.dir_z[k] = o[5];
            rh.ray.tnear[k] = 0.0f, rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
            rh.ray.time[k] = 0.0f, rh.ray.mask[k] = 0xFFFFFFFFu;
            rh.ray.id[k] = 0, rh.ray.flags[k] = 0;
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect8(valid, scene_, &context, &rh);
        for (std::size_t k = 0; k < W && first + k < n; ++k)
            t[first + k] = rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID
                               ? std::numeric_limits<double>::infinity()
                               : double(rh.ray.tfar[k]);
    }
}

SegmentHit EmbreeBackend::intersect(const float o[3], const float d[3]) const {
    SegmentHit h;
    const Vec3 origin{o[0], o[1], o[2]}, dir{d[0], d[1], d[2]};
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = embree_ray(o[0], o[1], o[2], d[0], d[1], d[2]);
    rtcIntersect1(scene_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        h.t = std::numeric_limits<double>::infinity();
        return h;
    }
    // Embree names the grid, not the triangle: find it from the point (the side of the cell's
    // diagonal, u + v = 1, as heightfield.h splits it).
    h.t = rh.ray.tfar, h.point = origin + h.t * dir;
    const double gx = h.point.x * inv_spacing_, gy = h.point.y * inv_spacing_;
    h.cell_x = std::clamp(int(std::floor(gx)), 0, n_ - 1);
    h.cell_y = std::clamp(int(std::floor(gy)), 0, n_ - 1);
    h.triangle = (gx - h.cell_x) + (gy - h.cell_y) <= 1.0 ? 0 : 1;
    return h;
}

void EmbreeBackend::trace(Vec3 o, const Vec3& d, double side, int max_wraps, const BeamEntry*,
                          SurfaceHit& r) const {
    const double period = box_.period, epsilon = box_.epsilon;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (r.wraps = 0; r.wraps <= max_wraps;) {
        // No far limit is needed: there is no geometry beyond the walls, and a straight ray that
        // leaves the box never comes back, so any hit lies inside the patch. The walls are only
        // needed when nothing is hit (below), which keeps their divisions off the hit path.
        RTCRayHit rh =
            embree_ray(float(o.x), float(o.y), float(o.z), float(d.x), float(d.y), float(d.z));
        rtcIntersect1(scene_, &context, &rh);
        if (recorder_)
            recorder_->insert(recorder_->end(), {rh.ray.org_x, rh.ray.org_y, rh.ray.org_z,
                                                 rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z});
        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            Vec3 ng{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
            ng = normalize(ng);
            const Vec3 up = ng.z < 0 ? -ng : ng; // a height field's facets face up
            Vec3 at = o + double(rh.ray.tfar) * d;
            if (side * dot(d, up) > 0) {
                // From above a ray meets a height field from above only (and from below only from
                // below). A facet met from the other side means the origin, rounded to float near
                // a sharp edge, lay an ulp across the surface: the ray crosses back here and goes
                // on unchanged.
                o = at + side * epsilon * up;
                ++r.reentries;
                if (r.reentries > 64) break; // not a rounding artefact: report the ray as lost
                continue;
            }
            r.kind = SurfaceHit::hit;
            r.normal = up;
            // Keep the position in the patch for the next segment (a hit lies within epsilon of
            // the walls, so one wrap suffices).
            if (at.x < 0) at.x += period;
            if (at.x >= period) at.x -= period;
            if (at.y < 0) at.y += period;
            if (at.y >= period) at.y -= period;
            r.position = at;
            return;
        }
        // Nothing hit: the ray leaves the box through the wall it meets first.
        const double inf = std::numeric_limits<double>::infinity();
        const double tx = d.x > 0 ? (period - o.x) / d.x : d.x < 0 ? -o.x / d.x : inf;
        const double ty = d.y > 0 ? (period - o.y) / d.y : d.y < 0 ? -o.y / d.y : inf;
        const double tz = d.z > 0   ? (box_.z_max + epsilon - o.z) / d.z
                          : d.z < 0 ? (box_.z_min - epsilon - o.z) / d.z
                                    : inf;
        const double t_wall = std::max(0.0, std::min({tx, ty, tz}));
        if (tz <= tx && tz <= ty) {
            r.kind = d.z > 0 ? SurfaceHit::escaped_up : SurfaceHit::escaped_down;
            return;
        }
        // Through a side wall: re-enter through the opposite one.
        o = o + t_wall * d;
        if (side * d.z <= 0 && crossed_before_wall(o, d, side, tx <= ty, ty <= tx, r)) return;
        if (tx <= ty) o.x = d.x > 0 ? 0.0 : period;
        if (ty <= tx) o.y = d.y > 0 ? 0.0 : period;
        ++r.wraps;
    }
    r.kind = SurfaceHit::lost;
}
} // namespace

const TraceBackendKind& embree_backend() {
    static const TraceBackendKind k{
        "embree", "Embree 3's BVH over a grid geometry (the reference)",
        [](const HeightField& s, const SceneBox& box) -> std::unique_ptr<TraceBackend> {
            return std::make_unique<EmbreeBackend>(s, box);
        }};
    return k;
}

} // namespace gonio
