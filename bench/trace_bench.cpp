// Ray-tracing benchmark (issue 4): on one 1024^2 Beckmann alpha = 0.75 surface, the full
// gonioreflectometer pipeline (beam, periodic wrapping, float-aware origins, perfect-mirror
// bounces, binning, ledger) against bare rtcIntersect1 calls on exactly the segments the pipeline
// gives Embree (all bounces and wraps, recorded). Segments per second, single- and two-threaded,
// and the ratio (best of three runs each). Not a test: numbers depend on the machine.
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

static double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

int main(int argc, char** argv) {
    const int n = argc > 1 ? std::atoi(argv[1]) : 1024;
    const long long rays = argc > 2 ? std::atoll(argv[2]) : 2097152;
    const double theta = argc > 3 ? std::atof(argv[3]) : 60.0;
    const std::string only = argc > 4 ? argv[4] : "both"; // one thread count, e.g. for perf
    SurfaceSpec spec;
    spec.size = n;
    const HeightField surface = generate_surface(Beckmann(0.75), spec, 2);
    Scene scene(surface);
    const BeckersSensor sensor(3240);
    const SpecularReflector mirror(FresnelTerm::mirror());
    const Vec3 wi = spherical_direction(radians(theta), 0.0);

    // The bare calls replay exactly the segments the pipeline gives Embree (recorded in one
    // single-threaded run; the pipeline is deterministic), with nothing else around them.
    TraceSettings st;
    st.rays = rays;
    std::vector<float> segments;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        scene.record_segments(&segments);
        trace_incidence(scene, mirror, sensor, wi, st);
        scene.record_segments(nullptr);
    }
    const size_t count = segments.size() / 6;
    std::printf("Beckmann alpha = 0.75, %d^2 surface, theta_i = %g deg, %lld beam rays, %zu "
                "segments\n",
                n, theta, (long long)std::llround(std::pow(std::ceil(std::sqrt(double(rays))), 2)),
                count);
    std::printf("%8s %16s %16s %8s\n", "threads", "pipeline_Mseg/s", "bare_Mseg/s", "ratio");
    for (int threads : {1, 2}) {
        if (only != "both" && only != std::to_string(threads)) continue;
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        // Best of three, alternating, so that both see the same machine state.
        double pipeline = 0, bare = 0;
        for (int repeat = 0; repeat < 3; ++repeat) {
            auto t0 = Clock::now();
            const TraceResult r = trace_incidence(scene, mirror, sensor, wi, st);
            pipeline = std::max(pipeline, double(r.segments) / seconds_since(t0));
            if (size_t(r.segments) != count) std::printf("warning: %lld segments\n", r.segments);
            t0 = Clock::now();
            std::vector<float> sink(count);
            tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096),
                              [&](const tbb::blocked_range<size_t>& b) {
                                  for (size_t k = b.begin(); k < b.end(); ++k)
                                      sink[k] =
                                          scene.intersect(&segments[6 * k], &segments[6 * k + 3]);
                              });
            bare = std::max(bare, double(count) / seconds_since(t0));
        }
        std::printf("%8d %16.2f %16.2f %8.2f\n", threads, pipeline / 1e6, bare / 1e6,
                    pipeline / bare);
    }
    return 0;
}
