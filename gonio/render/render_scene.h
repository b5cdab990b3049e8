#pragma once
// The scene a render shows: a procedurally made object standing on a floor, as Embree triangle
// meshes with smooth shading normals and tangents (for anisotropic BSDFs). Objects: a sphere, and
// a torus lying on the floor (concave: it sees itself, so inter-reflections show).
#include "core/enum_names.h"
#include "core/math.h"

#include <embree3/rtcore.h>
#include <string>
#include <vector>

namespace gonio {

struct SceneHit {
    bool hit = false;
    bool object = false; // false: the floor
    double t = 0;
    Vec3 p, ng, n, tangent; // position, geometric normal, shading normal, shading tangent
};

enum class RenderObject { sphere, torus };
template <>
struct EnumNames<RenderObject> {
    static constexpr const char* what = "object";
    static constexpr const char* names[] = {"sphere", "torus"};
};

class RenderScene {
  public:
    explicit RenderScene(RenderObject object);
    ~RenderScene();
    RenderScene(const RenderScene&) = delete;
    RenderScene& operator=(const RenderScene&) = delete;

    SceneHit intersect(const Vec3& origin, const Vec3& direction) const;
    bool occluded(const Vec3& origin, const Vec3& direction) const;
    // Where the camera looks and how far the object extends (for framing).
    Vec3 centre() const { return centre_; }
    double radius() const { return radius_; }

  private:
    struct Mesh {
        std::vector<float> position; // 3 per vertex
        std::vector<Vec3> normal, tangent;
        std::vector<unsigned> index; // 3 per triangle
        bool object = true;
    };
    void add(Mesh mesh);
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<Mesh> meshes_;
    Vec3 centre_;
    double radius_ = 1;
};

} // namespace gonio
