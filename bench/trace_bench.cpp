// Ray-tracing benchmark (issue 4): on one 1024^2 Beckmann alpha = 0.75 surface, the full
// gonioreflectometer pipeline (beam, periodic wrapping, float-aware origins, perfect-mirror
// bounces, binning, ledger) against bare rtcIntersect1 calls on the same rays: the beam's
// primary rays and their first reflections, as the pipeline issues them. Segments per second,
// single- and two-threaded, and the ratio. Not a test: numbers depend on the machine.
//
// Usage: trace_bench [size=1024] [rays=2097152] [theta_i_deg=60] [threads=both|1|2]
#include "gonio/trace/gonioreflectometer.h"
#include "heightfield/generate.h"
#include "heightfield/ndf/beckmann.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <vector>

using namespace gonio;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
    const int n = argc > 1 ? std::atoi(argv[1]) : 1024;
    const long long rays = argc > 2 ? std::atoll(argv[2]) : 2097152;
    const double theta = argc > 3 ? std::atof(argv[3]) : 60.0;
    const std::string only = argc > 4 ? argv[4] : "both"; // one thread count, e.g. for perf
    SurfaceSpec spec;
    spec.size = n;
    const HeightField surface = generate_surface(Beckmann(0.75), spec, 2);
    const Scene scene(surface);
    const BeckersSensor sensor(3240);
    const SpecularReflector mirror(FresnelTerm::mirror());
    const Vec3 wi = spherical_direction(radians(theta), 0.0);

    // The same rays for the bare calls: the beam's primary rays and their first reflections.
    const long long side = (long long)std::ceil(std::sqrt(double(rays)));
    std::vector<Vec3> org, dir;
    {
        Rng rng{1, 0};
        const double L = scene.period(), eps = scene.epsilon();
        for (long long r = 0; r < side * side; ++r) {
            const Vec3 o{(double(r % side) + rng.uniform()) / side * L,
                         (double(r / side) + rng.uniform()) / side * L, scene.z_max() + eps};
            org.push_back(o), dir.push_back(-wi);
            const SurfaceHit h = scene.trace(o, -wi);
            if (h.kind != SurfaceHit::hit) continue;
            org.push_back(h.position + eps * h.normal),
                dir.push_back(normalize(reflect(wi, h.normal)));
        }
    }
    std::printf(
        "Beckmann alpha = 0.75, %d^2 surface, theta_i = %g deg, %lld beam rays, %zu bare rays\n", n,
        theta, side * side, org.size());
    std::printf("%8s %16s %16s %8s\n", "threads", "pipeline_Mseg/s", "bare_Mseg/s", "ratio");
    for (int threads : {1, 2}) {
        if (only != "both" && only != std::to_string(threads)) continue;
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        TraceSettings st;
        st.rays = rays;
        auto t0 = Clock::now();
        const TraceResult r = trace_incidence(scene, mirror, sensor, wi, st);
        const double pipeline =
            double(r.segments) / std::chrono::duration<double>(Clock::now() - t0).count();
        t0 = Clock::now();
        std::vector<float> sink(org.size());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, org.size(), 4096),
                          [&](const tbb::blocked_range<size_t>& b) {
                              for (size_t k = b.begin(); k < b.end(); ++k)
                                  sink[k] = scene.intersect(org[k], dir[k], 1e30f);
                          });
        const double bare =
            double(org.size()) / std::chrono::duration<double>(Clock::now() - t0).count();
        std::printf("%8d %16.2f %16.2f %8.2f\n", threads, pipeline / 1e6, bare / 1e6,
                    pipeline / bare);
    }
    return 0;
}
