// Ray-tracing benchmark (issues 4 and 19): the two trace backends on the same rays.
//
// speed (default): the whole gonioreflectometer pipeline (beam, periodic wrapping, origins,
// perfect-mirror bounces, binning, ledger) on Beckmann alpha = 0.75 surfaces, 256^2, 1024^2 and
// 4096^2, theta_i 0, 60, 85 and 89.9 deg, 1 and 2 threads, with the Embree backend and the
// height-field traversal: the same random streams, so the same beam rays. Beam rays per second,
// segments per second (a segment: one straight piece of a ray between bounces and walls), the
// memory of each acceleration structure, and the speed-up (best of `repeats` runs each,
// alternating). Beside each, the beam rays' first hits alone through Embree one by one, Embree's
// packets of 8 (rtcIntersect8) and the height field. The last lines: the 1024^2, 2-thread
// speed-up at theta_i 89.9 deg, the beam rays' against Embree's best, and the speed-up at 60 deg
// (the sizes and angles run, when --size or --theta picks others).
//
// hits: hit for hit. The segments the Embree pipeline gives Embree (every bounce and wrap,
// recorded) replayed through both backends; each segment's first hit compared (same triangle,
// t within 1e-5 relative), mismatches counted and the first ones printed. Beckmann and GGX,
// alpha 0.1 to 2, theta_i 0 to 89.9 deg, 64^2 to 4096^2.
//
// Not a test: the speeds depend on the machine. --quick runs a small version of either (CTest).
//
// Usage: trace_bench [speed|hits] [--quick] [--rays N] [--repeats R] [--size N] [--theta DEG]
#include "gonio/trace/backend_comparison.h"
#include "gonio/trace/gonioreflectometer.h"
#include "heightfield/generate.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tuple>
#include <vector>

using namespace gonio;
using Clock = std::chrono::steady_clock;

namespace {
double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

HeightField surface_of(const Ndf& ndf, int n) {
    SurfaceSpec spec;
    spec.size = n;
    spec.iterations = 100; // the slopes' distribution is what matters for tracing, not its last %
    return generate_surface(ndf, spec, 2);
}

struct Rate {
    double rays_per_s = 0, segments_per_s = 0;
    long long segments = 0;
};

// The backends alone (one bare call per segment) on the segments the Embree pipeline traced.
// Returns the segments per second of each (Embree, the height field).
std::pair<double, double> bare_rates(Scene& embree, const Scene& walk, const Material& material,
                                     const BeckersSensor& sensor, const Vec3& wi,
                                     const TraceSettings& st, int threads, int repeats) {
    std::vector<float> segs;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        embree.record_segments(&segs);
        trace_incidence(embree, material, sensor, wi, st);
        embree.record_segments(nullptr);
    }
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const size_t count = segs.size() / 6;
    double best[2] = {0, 0};
    std::vector<double> sink(count);
    for (int r = 0; r < repeats; ++r)
        for (int k = 0; k < 2; ++k) {
            const Scene& s = k == 0 ? embree : walk;
            const auto t = Clock::now();
            tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096),
                              [&](const tbb::blocked_range<size_t>& b) {
                                  for (size_t i = b.begin(); i < b.end(); ++i)
                                      sink[i] = s.intersect(&segs[6 * i], &segs[6 * i + 3]).t;
                              });
            best[k] = std::max(best[k], double(count) / seconds_since(t));
        }
    std::printf("    bare segments, %d thread(s): embree %.3f Mseg/s, heightfield %.3f Mseg/s, "
                "ratio %.2f\n",
                threads, best[0] / 1e6, best[1] / 1e6, best[1] / best[0]);
    return {best[0], best[1]};
}

// The honest baseline: beam rays alone (coherent: neighbours in a packet), first hits through
// Embree one by one (rtcIntersect1), Embree's packets of 8 (rtcIntersect8), and the height
// field. The segments start just above the surface's top, spread over the patch in rows as a
// beam's are; a segment that leaves through a side wall is a miss for all three.
struct BeamRates {
    double embree1 = 0, embree8 = 0, heightfield = 0; // rays per second, best of the repeats
    long long rays = 0, packet_disagree = 0, heightfield_disagree = 0; // against rtcIntersect1
};
BeamRates beam_rates(const Scene& embree, const Scene& walk, const Vec3& wi, long long rays,
                     int threads, int repeats) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const long long side = std::max(1LL, (long long)std::sqrt(double(rays)));
    const size_t count = size_t(side * side);
    std::vector<float> segs(6 * count);
    const double L = walk.period(), z = walk.z_max() + walk.epsilon();
    for (size_t i = 0; i < count; ++i) {
        float* s = &segs[6 * i];
        s[0] = float((double(i % size_t(side)) + 0.5) / double(side) * L);
        s[1] = float((double(i / size_t(side)) + 0.5) / double(side) * L);
        s[2] = float(z);
        s[3] = float(-wi.x), s[4] = float(-wi.y), s[5] = float(-wi.z);
    }
    std::vector<double> t(count), single;
    BeamRates best;
    const size_t grain = 4096; // a multiple of the packet width
    for (int r = 0; r < repeats; ++r)
        for (int k = 0; k < 3; ++k) {
            const auto t0 = Clock::now();
            tbb::parallel_for(tbb::blocked_range<size_t>(0, count, grain),
                              [&](const tbb::blocked_range<size_t>& b) {
                                  const float* from = &segs[6 * b.begin()];
                                  if (k == 1)
                                      embree.intersect_packets(from, b.size(), &t[b.begin()]);
                                  else
                                      for (size_t i = b.begin(); i < b.end(); ++i)
                                          t[i] = (k == 0 ? embree : walk)
                                                     .intersect(&segs[6 * i], &segs[6 * i + 3])
                                                     .t;
                              });
            double& b = k == 0 ? best.embree1 : k == 1 ? best.embree8 : best.heightfield;
            b = std::max(b, double(count) / seconds_since(t0));
            if (r == 0 && k == 0) single = t;
            if (r == 0 && k > 0) // the same hits: t within 1e-6 relative, or both none
                for (size_t i = 0; i < count; ++i)
                    if (!(t[i] == single[i] || std::abs(t[i] - single[i]) <= 1e-6 * single[i]))
                        ++(k == 1 ? best.packet_disagree : best.heightfield_disagree);
        }
    best.rays = (long long)count;
    return best;
}

int speed(bool quick, long long rays, int repeats, int only_size, double only_theta, bool bare,
          const std::string& only_backend) {
    std::vector<int> sizes = quick ? std::vector<int>{256} : std::vector<int>{256, 1024, 4096};
    std::vector<double> thetas =
        quick ? std::vector<double>{60} : std::vector<double>{0, 60, 85, 89.9};
    if (only_size > 0) sizes = {only_size};
    if (only_theta >= 0) thetas = {only_theta};
    const BeckersSensor sensor(3240);
    const SpecularReflector mirror(FresnelTerm::mirror());
    TraceSettings st;
    st.rays = rays;
    std::printf("Beckmann alpha = 0.75, perfect mirror, %lld beam rays per run, best of %d\n",
                (long long)rays, repeats);
    std::printf("%6s %6s %7s | %12s %9s | %12s %9s | %7s\n", "size", "theta", "threads",
                "embree ray/s", "Mseg/s", "hfield ray/s", "Mseg/s", "speedup");
    // Speed-ups at 2 threads by (size, theta), for the summary lines.
    std::map<std::pair<int, double>, double> two_threads;
    // The height field's beam rays against Embree's best (one by one or in packets).
    std::map<std::pair<int, double>, double> beam_two_threads;
    std::vector<std::string> memory;
    for (int n : sizes) {
        const HeightField surface = surface_of(Beckmann(0.75), n);
        auto t0 = Clock::now();
        Scene embree(surface, embree_backend());
        const double embree_build = seconds_since(t0);
        t0 = Clock::now();
        const Scene walk(surface, heightfield_backend());
        const double walk_build = seconds_since(t0);
        // The height field traced by its scalar walk, one ray at a time: what the lanes gain.
        setenv("GONIO_HEIGHTFIELD_LANES", "0", 1);
        const Scene scalar_walk(surface, heightfield_backend());
        unsetenv("GONIO_HEIGHTFIELD_LANES");
        char line[200];
        std::snprintf(line, sizeof line, "%6d %14.1f %10.3f %14.1f %10.3f %8.1f %10.1f", n,
                      embree.memory_bytes() / 1048576.0, embree_build,
                      walk.memory_bytes() / 1048576.0, walk_build,
                      double(embree.memory_bytes()) / double(walk.memory_bytes()),
                      (walk.z_max() - walk.z_min()) / surface.spacing);
        memory.push_back(line);
        for (double theta : thetas) {
            const Vec3 wi = spherical_direction(radians(theta), 0.0);
            for (int threads : {1, 2}) {
                tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
                Rate e, h, hs;
                for (int r = 0; r < repeats; ++r)
                    for (const Scene* s :
                         {static_cast<const Scene*>(&embree), &walk, &scalar_walk}) {
                        if (!only_backend.empty() && only_backend != s->backend().name) continue;
                        const auto t = Clock::now();
                        const TraceResult res = trace_incidence(*s, mirror, sensor, wi, st);
                        const double sec = seconds_since(t);
                        Rate& k = s == &embree ? e : s == &walk ? h : hs;
                        k.rays_per_s = std::max(k.rays_per_s, double(res.rays) / sec);
                        k.segments_per_s = std::max(k.segments_per_s, double(res.segments) / sec);
                        k.segments = res.segments;
                    }
                if (hs.rays_per_s > 0)
                    std::printf("    height field in SIMD lanes against its scalar walk, %d "
                                "thread(s): %.0f against %.0f ray/s, ratio %.2f\n",
                                threads, h.rays_per_s, hs.rays_per_s, h.rays_per_s / hs.rays_per_s);
                if (bare) {
                    // A ray's time split: its segments' traversal (the bare rate) and the rest
                    // (beam, binning, random numbers, Fresnel, ledger).
                    const auto [e_seg, h_seg] =
                        bare_rates(embree, walk, mirror, sensor, wi, st, threads, repeats);
                    for (const auto& [name, rate, seg] :
                         {std::tuple{"embree", e, e_seg}, std::tuple{"heightfield", h, h_seg}}) {
                        const double per_ray = 1e9 / rate.rays_per_s;
                        const double traversal = 1e9 * rate.segments_per_s / rate.rays_per_s / seg;
                        std::printf("    %s, %d thread(s): %.0f ns a ray = traversal %.0f + the "
                                    "rest %.0f (%.2f segments a ray)\n",
                                    name, threads, per_ray, traversal, per_ray - traversal,
                                    rate.segments_per_s / rate.rays_per_s);
                    }
                }
                const BeamRates beam = beam_rates(embree, walk, wi, rays, threads, repeats);
                std::printf("    beam rays' first hits, %d thread(s): embree %.3f Mray/s, embree "
                            "packets of 8 %.3f Mray/s, heightfield %.3f Mray/s (of %lld rays, "
                            "%lld and %lld hit elsewhere than rtcIntersect1)\n",
                            threads, beam.embree1 / 1e6, beam.embree8 / 1e6, beam.heightfield / 1e6,
                            beam.rays, beam.packet_disagree, beam.heightfield_disagree);
                const double speedup = h.rays_per_s / e.rays_per_s;
                std::printf("%6d %6.1f %7d | %12.0f %9.3f | %12.0f %9.3f | %7.2f\n", n, theta,
                            threads, e.rays_per_s, e.segments_per_s / 1e6, h.rays_per_s,
                            h.segments_per_s / 1e6, speedup);
                std::fflush(stdout);
                if (threads == 2) {
                    two_threads[{n, theta}] = speedup;
                    beam_two_threads[{n, theta}] =
                        beam.heightfield / std::max(beam.embree1, beam.embree8);
                }
            }
        }
    }
    std::printf("\nacceleration structure memory (MiB), build time (s), and the surface's relief "
                "(z_max - z_min, in samples):\n");
    std::printf("%6s %14s %10s %14s %10s %8s %10s\n", "size", "embree MiB", "build s", "hfield MiB",
                "build s", "ratio", "relief");
    for (const std::string& l : memory) std::printf("%s\n", l.c_str());
    // The summary lines at 1024^2 (or the one size run), the last one at theta_i 60 deg (or the
    // first angle run): the grazing line only where 89.9 deg was run.
    const int at = std::find(sizes.begin(), sizes.end(), 1024) != sizes.end() ? 1024 : sizes[0];
    const double headline_theta =
        std::find(thetas.begin(), thetas.end(), 60.0) != thetas.end() ? 60.0 : thetas[0];
    if (headline_theta != 89.9 && two_threads.count({at, 89.9}))
        std::printf("speedup heightfield/embree at grazing incidence (%d\u00b2, \u03b1 0.75, "
                    "\u03b8i 89.9\u00b0, 2 threads): %.2f\n",
                    at, two_threads[{at, 89.9}]);
    std::printf("beam rays' first hits, heightfield against Embree's best of rtcIntersect1 and "
                "rtcIntersect8 (%d\u00b2, \u03b8i %g\u00b0, 2 threads): %.2f\n",
                at, headline_theta, beam_two_threads[{at, headline_theta}]);
    std::printf("speedup heightfield/embree (%d\u00b2, \u03b1 0.75, \u03b8i %g\u00b0, 2 threads): "
                "%.2f\n",
                at, headline_theta, two_threads[{at, headline_theta}]);
    return 0;
}

int hits(bool quick, long long rays, int only_size) {
    struct Case {
        const char* ndf;
        double alpha;
        int n;
    };
    std::vector<Case> cases;
    std::vector<int> sizes = quick ? std::vector<int>{64} : std::vector<int>{64, 256, 1024, 4096};
    if (only_size > 0) sizes = {only_size};
    const std::vector<double> alphas =
        quick ? std::vector<double>{0.5} : std::vector<double>{0.1, 0.5, 1.0, 2.0};
    for (int n : sizes)
        for (const char* ndf : {"beckmann", "ggx"})
            for (double a : alphas) cases.push_back({ndf, a, n});
    const std::vector<double> thetas =
        quick ? std::vector<double>{60, 89.9} : std::vector<double>{0, 60, 85, 89.9};
    const BeckersSensor sensor(578);
    const SpecularReflector mirror(FresnelTerm::mirror());
    TraceSettings st;
    st.rays = rays;
    st.batches = 4;
    std::printf("%9s %5s %5s %6s %11s %9s %9s %8s %7s %7s %7s %7s %7s %9s\n", "ndf", "alpha",
                "size", "theta", "segments", "hits", "edge", "missed", "only_e", "only_h", "tri",
                "t", "e_float", "max_rel_t");
    BackendComparison all;
    for (const Case& c : cases) {
        std::unique_ptr<Ndf> ndf;
        if (std::strcmp(c.ndf, "ggx") == 0)
            ndf = std::make_unique<Ggx>(c.alpha);
        else
            ndf = std::make_unique<Beckmann>(c.alpha);
        const HeightField surface = surface_of(*ndf, c.n);
        Scene embree(surface, embree_backend());
        const Scene walk(surface, heightfield_backend());
        for (double theta : thetas) {
            std::vector<float> segments;
            {
                tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
                embree.record_segments(&segments);
                trace_incidence(embree, mirror, sensor, spherical_direction(radians(theta), 0.3),
                                st);
                embree.record_segments(nullptr);
            }
            const BackendComparison r = compare_backends(embree, walk, segments);
            std::printf("%9s %5.2f %5d %6.1f %11lld %9lld %9lld %8lld %7lld %7lld %7lld %7lld "
                        "%7lld %9.2e\n",
                        c.ndf, c.alpha, c.n, theta, r.segments, r.agree, r.on_shared_edge,
                        r.both_missed, r.only_reference, r.only_other, r.other_triangle,
                        r.t_differs, r.reference_rounding, r.max_t_relative);
            std::fflush(stdout);
            for (const std::string& e : r.examples) std::printf("    %s\n", e.c_str());
            all.add(r);
        }
    }
    std::printf("all: %lld segments, %lld mismatches (%.3g of the segments): %lld only Embree hit, "
                "%lld only the traversal, %lld other triangle, %lld t beyond 1e-5; and %lld where "
                "Embree's float arithmetic differs from the exact answer (t or a grazed crease; "
                "the traversal "
                "agrees with it)\n",
                all.segments, all.mismatches(), double(all.mismatches()) / double(all.segments),
                all.only_reference, all.only_other, all.other_triangle, all.t_differs,
                all.reference_rounding);
    return 0;
}
} // namespace

int main(int argc, char** argv) {
    std::string mode = "speed";
    bool quick = false;
    long long rays = -1;
    int repeats = 3, only_size = 0;
    bool bare = false;
    std::string only_backend; // for profiling one backend
    double only_theta = -1;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--quick")
            quick = true;
        else if (a == "--rays" && i + 1 < argc)
            rays = std::atoll(argv[++i]);
        else if (a == "--backend" && i + 1 < argc)
            only_backend = argv[++i];
        else if (a == "--bare")
            bare = true;
        else if (a == "--size" && i + 1 < argc)
            only_size = std::atoi(argv[++i]);
        else if (a == "--theta" && i + 1 < argc)
            only_theta = std::atof(argv[++i]);
        else if (a == "--repeats" && i + 1 < argc)
            repeats = std::atoi(argv[++i]);
        else if (a == "speed" || a == "hits")
            mode = a;
        else {
            std::fprintf(stderr, "usage: trace_bench [speed|hits] [--quick] [--rays N] "
                                 "[--repeats R] [--size N] [--theta DEG]\n");
            return 2;
        }
    }
    if (mode == "hits") return hits(quick, rays > 0 ? rays : quick ? 1 << 14 : 1 << 17, only_size);
    return speed(quick,
                 rays > 0 ? rays
                 : quick  ? 1 << 16
                          : 1 << 20,
                 repeats, only_size, only_theta, bare, only_backend);
}
