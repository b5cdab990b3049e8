#pragma once
// A small path tracer for looking at a tabulated BSDF: a pinhole camera on an object standing on a
// grey Lambertian floor, lit by an environment and optionally a directional light. At every
// vertex: next-event estimation of the environment and of the light, and a BSDF sample, the two
// environment strategies combined by multiple importance sampling (power heuristic; Veach 1997,
// Eq. 9.13); paths end at `max_depth` vertices, so direct light plus inter-reflections up to that
// depth. Every pixel has its own random stream (seed, pixel): an image is the same for any thread
// count.
#include "gonio/render/environment.h"
#include "gonio/render/image.h"
#include "gonio/render/render_scene.h"
#include "gonio/render/surface_bsdf.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace gonio {

struct RenderSettings {
    int width = 400, height = 300;
    int spp = 64;
    int max_depth = 5;
    std::uint64_t seed = 1;
    bool light = false;
    Vec3 light_direction{0, 0, 1}; // towards the light
    double light_irradiance = 1.5; // on a surface facing it
    double camera_elevation_deg = 22, camera_azimuth_deg = -60, fov_deg = 32;
    // Told after each band of rows: rows done, of `height` (the command line's progress line).
    std::function<void(int rows_done, int rows)> progress;
};

struct RenderResult {
    Image image;
    std::vector<std::uint8_t> object; // per pixel: the camera ray hits the object
    // The pixels' Monte Carlo noise over the object: the rms of each pixel's standard error (from
    // the difference of its even and odd samples) over the rms of the pixels' luminance.
    double relative_noise = 0;
    double seconds = 0;
};

RenderResult render(const RenderScene& scene, const Environment& env, const SurfaceBsdf& object,
                    const SurfaceBsdf& floor, const RenderSettings& settings);

} // namespace gonio
