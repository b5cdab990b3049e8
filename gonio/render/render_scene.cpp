#include "gonio/render/render_scene.h"
#include "gonio/trace/embree_device.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace gonio {

namespace {
// A (u, v) grid of `nu` x `nv` quads over a closed parametric surface, periodic in u (and in v when
// `wrap_v`), with positions, normals and u-tangents from `at(u, v)`.
template <class F>
void grid(int nu, int nv, bool wrap_v, F at, std::vector<float>& pos, std::vector<Vec3>& nrm,
          std::vector<Vec3>& tan, std::vector<unsigned>& idx) {
    const int rows = wrap_v ? nv : nv + 1;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < nu; ++i) {
            Vec3 p, n, t;
            at(double(i) / nu, double(j) / nv, p, n, t);
            pos.insert(pos.end(), {float(p.x), float(p.y), float(p.z)});
            nrm.push_back(n);
            tan.push_back(t);
        }
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const unsigned i1 = unsigned((i + 1) % nu),
                           j1 = unsigned(wrap_v ? (j + 1) % nv : j + 1);
            const unsigned a = unsigned(j) * nu + i, b = unsigned(j) * nu + i1, c = j1 * nu + i1,
                           d = j1 * nu + i;
            idx.insert(idx.end(), {a, b, c, a, c, d});
        }
}
} // namespace

RenderScene::RenderScene(RenderObject object) {
    Mesh m;
    if (object == RenderObject::sphere) {
        centre_ = {0, 0, 1};
        radius_ = 1;
        grid(
            192, 96, false,
            [](double u, double v, Vec3& p, Vec3& n, Vec3& t) {
                const double phi = kTwoPi * u, theta = kPi * v;
                n = spherical_direction(theta, phi);
                p = n + Vec3{0, 0, 1};
                t = {-std::sin(phi), std::cos(phi), 0};
            },
            m.position, m.normal, m.tangent, m.index);
    } else {
        const double R = 1.0, r = 0.45; // lying on the floor: its axis is z
        centre_ = {0, 0, r};
        radius_ = R + r;
        grid(
            256, 128, true,
            [&](double u, double v, Vec3& p, Vec3& n, Vec3& t) {
                const double a = kTwoPi * u, b = kTwoPi * v;
                n = {std::cos(b) * std::cos(a), std::cos(b) * std::sin(a), std::sin(b)};
                p = Vec3{R * std::cos(a), R * std::sin(a), r} + r * n;
                t = {-std::sin(a), std::cos(a), 0};
            },
            m.position, m.normal, m.tangent, m.index);
    }
    device_ = new_embree_device();
    if (!device_) throw std::runtime_error("Embree: cannot create a device");
    scene_ = rtcNewScene(device_);
    add(std::move(m));
    // The floor: a large square at z = 0.
    Mesh floor;
    floor.object = false;
    const float s = 50;
    floor.position = {-s, -s, 0, s, -s, 0, s, s, 0, -s, s, 0};
    floor.normal.assign(4, {0, 0, 1});
    floor.tangent.assign(4, {1, 0, 0});
    floor.index = {0, 1, 2, 0, 2, 3};
    add(std::move(floor));
    rtcCommitScene(scene_);
}

RenderScene::~RenderScene() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
}

void RenderScene::add(Mesh mesh) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    const size_t nv = mesh.position.size() / 3, nt = mesh.index.size() / 3;
    float* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    std::copy(mesh.position.begin(), mesh.position.end(), v);
    unsigned* i = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt));
    std::copy(mesh.index.begin(), mesh.index.end(), i);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene_, g, unsigned(meshes_.size()));
    rtcReleaseGeometry(g);
    meshes_.push_back(std::move(mesh));
}

SceneHit RenderScene::intersect(const Vec3& o, const Vec3& d) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = float(o.x), rh.ray.org_y = float(o.y), rh.ray.org_z = float(o.z);
    rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
    rh.ray.tnear = 0;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx, &rh);
    SceneHit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    const Mesh& m = meshes_[rh.hit.geomID];
    const unsigned* tri = m.index.data() + 3 * size_t(rh.hit.primID);
    const double u = rh.hit.u, v = rh.hit.v, w = 1 - u - v;
    h.hit = true;
    h.object = m.object;
    h.t = rh.ray.tfar;
    h.p = o + d * h.t;
    h.ng = normalize(Vec3{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
    h.n = normalize(m.normal[tri[0]] * w + m.normal[tri[1]] * u + m.normal[tri[2]] * v);
    h.tangent = m.tangent[tri[0]] * w + m.tangent[tri[1]] * u + m.tangent[tri[2]] * v;
    if (dot(h.ng, h.n) < 0) h.ng = -h.ng; // the meshes' windings vary: face the shading normal
    return h;
}

bool RenderScene::occluded(const Vec3& o, const Vec3& d) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r{};
    r.org_x = float(o.x), r.org_y = float(o.y), r.org_z = float(o.z);
    r.dir_x = float(d.x), r.dir_y = float(d.y), r.dir_z = float(d.z);
    r.tnear = 0;
    r.tfar = std::numeric_limits<float>::infinity();
    r.mask = ~0u;
    rtcOccluded1(scene_, &ctx, &r);
    return r.tfar < 0;
}

} // namespace gonio
