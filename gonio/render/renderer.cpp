#include "gonio/render/renderer.h"

#include "core/parallel.h"
#include "core/random.h"

#include <chrono>
#include <cmath>
#include <tbb/blocked_range.h>

namespace gonio {

namespace {
struct Frame {
    Vec3 t, b, n;
    Vec3 to_local(const Vec3& d) const { return {dot(d, t), dot(d, b), dot(d, n)}; }
    Vec3 to_world(const Vec3& d) const { return t * d.x + b * d.y + n * d.z; }
};
Frame frame_of(const SceneHit& h) {
    Vec3 t = h.tangent - h.n * dot(h.n, h.tangent);
    if (dot(t, t) < 1e-12)
        t = std::abs(h.n.x) < 0.9 ? cross(h.n, {1, 0, 0}) : cross(h.n, {0, 1, 0});
    t = normalize(t);
    return {t, cross(h.n, t), h.n};
}
double power_heuristic(double a, double b) {
    return a * a / (a * a + b * b);
}
} // namespace

RenderResult render(const RenderScene& scene, const Environment& env, const SurfaceBsdf& object,
                    const SurfaceBsdf& floor, const RenderSettings& s) {
    const auto start = std::chrono::steady_clock::now();
    RenderResult out;
    out.image = Image(s.width, s.height);
    out.object.assign(size_t(s.width) * s.height, 0);
    // Camera framing the object: its bounding sphere fills about 70 % of the height.
    const double el = radians(s.camera_elevation_deg), az = radians(s.camera_azimuth_deg);
    const double tan_half = std::tan(radians(s.fov_deg) / 2);
    const double distance = scene.radius() / (0.7 * tan_half);
    const Vec3 target = scene.centre();
    const Vec3 eye =
        target +
        Vec3{std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)} * distance;
    const Vec3 forward = normalize(target - eye);
    const Vec3 right = normalize(cross(forward, {0, 0, 1}));
    const Vec3 up = cross(right, forward);
    const double aspect = double(s.width) / s.height;
    const Vec3 light = normalize(s.light_direction);

    auto radiance = [&](Vec3 o, Vec3 d, Rng& rng, bool& hit_object) {
        Rgb L{0, 0, 0}, T{1, 1, 1};
        double bsdf_pdf = 0; // of the last BSDF sample (0: a camera ray)
        for (int depth = 0;; ++depth) {
            const SceneHit h = scene.intersect(o, d);
            if (depth == 0) hit_object = h.hit && h.object;
            if (!h.hit) {
                const Rgb le = env.radiance(d);
                const double w = bsdf_pdf > 0 ? power_heuristic(bsdf_pdf, env.pdf(d)) : 1.0;
                for (int c = 0; c < 3; ++c) L[c] += T[c] * le[c] * w;
                break;
            }
            if (depth >= s.max_depth) break;
            const Frame f = frame_of(h);
            const Vec3 v = f.to_local(-d);
            if (v.z <= 0 || dot(-d, h.ng) <= 0) break; // seen from behind
            const SurfaceBsdf& bsdf = h.object ? object : floor;
            const Vec3 p = h.p + h.ng * (1e-4 * (1 + scene.radius()));
            auto shade = [&](const Vec3& l_world, const Rgb& le, double weight) {
                const Vec3 l = f.to_local(l_world);
                if (l.z <= 0 || dot(l_world, h.ng) <= 0 || scene.occluded(p, l_world)) return;
                const Rgb fr = bsdf.eval(v, l);
                for (int c = 0; c < 3; ++c) L[c] += T[c] * fr[c] * l.z * le[c] * weight;
            };
            // The environment, by its own sampling (weighted against the BSDF's).
            double env_pdf = 0;
            const Vec3 le_dir = env.sample(rng.uniform(), rng.uniform(), env_pdf);
            if (env_pdf > 0) {
                const double w = power_heuristic(env_pdf, bsdf.pdf(v, f.to_local(le_dir)));
                shade(le_dir, env.radiance(le_dir), w / env_pdf);
            }
            if (s.light)
                shade(light, {s.light_irradiance, s.light_irradiance, s.light_irradiance}, 1.0);
            // The BSDF sample continues the path.
            Vec3 l;
            double pdf = 0;
            if (!bsdf.sample(v, rng.uniform(), rng.uniform(), rng.uniform(), l, pdf) || pdf <= 0)
                break;
            const Vec3 l_world = f.to_world(l);
            if (dot(l_world, h.ng) <= 0) break;
            const Rgb fr = bsdf.eval(v, l);
            for (int c = 0; c < 3; ++c) T[c] *= fr[c] * l.z / pdf;
            if (T[0] + T[1] + T[2] <= 0) break;
            o = p;
            d = l_world;
            bsdf_pdf = pdf;
        }
        return L;
    };

    std::vector<double> noise(size_t(s.width) * s.height, 0.0);
    const int band = 8;
    for (int y0 = 0; y0 < s.height; y0 += band) {
        const int y1 = std::min(s.height, y0 + band);
        parallel_for_ranges<int>(
            y0 * s.width, y1 * s.width, 16, [&](const tbb::blocked_range<int>& r) {
                for (int pixel = r.begin(); pixel != r.end(); ++pixel) {
                    const int x = pixel % s.width, y = pixel / s.width;
                    Rng rng{s.seed, std::uint64_t(pixel)};
                    Rgb sum{0, 0, 0};
                    double halves[2] = {0, 0};
                    int object_hits = 0;
                    for (int k = 0; k < s.spp; ++k) {
                        const double px = (x + rng.uniform()) / s.width * 2 - 1;
                        const double py = 1 - (y + rng.uniform()) / s.height * 2;
                        const Vec3 d = normalize(forward + right * (px * tan_half * aspect) +
                                                 up * (py * tan_half));
                        bool hit_object = false;
                        const Rgb L = radiance(eye, d, rng, hit_object);
                        object_hits += hit_object;
                        for (int c = 0; c < 3; ++c) sum[c] += L[c];
                        halves[k & 1] += 0.2126 * L[0] + 0.7152 * L[1] + 0.0722 * L[2];
                    }
                    float* out_px = out.image.at(x, y);
                    for (int c = 0; c < 3; ++c) out_px[c] = float(sum[c] / s.spp);
                    out.object[size_t(pixel)] = object_hits * 2 > s.spp;
                    const int even = (s.spp + 1) / 2, odd = s.spp / 2;
                    noise[size_t(pixel)] =
                        odd > 0 ? 0.5 * (halves[0] / even - halves[1] / odd) : 0.0;
                }
            });
        if (s.progress) s.progress(y1, s.height);
    }
    double se2 = 0, v2 = 0;
    for (size_t k = 0; k < noise.size(); ++k)
        if (out.object[k]) {
            const float* p = out.image.rgb.data() + 3 * k;
            const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            se2 += noise[k] * noise[k];
            v2 += y * y;
        }
    out.relative_noise = v2 > 0 ? std::sqrt(se2 / v2) : 0.0;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace gonio
