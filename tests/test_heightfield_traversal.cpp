// The height-field traversal (trace.backend = "heightfield") held to Embree: hit for hit on the
// segments the pipeline gives Embree (above and below the surface), watertight at vertices and
// edges, the same SurfaceHit through Scene::trace (wraps, origin rules) for rays meeting and
// leaving the surface, and whole runs equal within their Monte Carlo error with every ledger
// closed.
#include "core/config_error.h"
#include "gonio/config/config.h"
#include "gonio/trace/backend_comparison.h"
#include "gonio/trace/gonioreflectometer.h"
#include "heightfield/generate.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"

#include <array>
#include <cmath>
#include <doctest/doctest.h>
#include <hwy/targets.h>
#include <memory>
#include <random>
#include <tbb/global_control.h>
#include <utility>

using namespace gonio;

namespace {
HeightField surface_of(const Ndf& ndf, int n, std::uint64_t seed = 1) {
    SurfaceSpec s;
    s.size = n;
    // The pool's path, on which the workloads below (segment counts) were sized; the traversal
    // does not care how the surface was made.
    s.target = MatchTarget::pool;
    s.iterations = 40;
    s.seed = seed;
    return generate_surface(ndf, s, 2);
}

// A random direction with cos(theta) = u^3 (many grazing ones), its z of the given sign.
Vec3 mostly_grazing(std::mt19937_64& rng, double z_sign) {
    std::uniform_real_distribution<double> u(0, 1);
    const double theta = std::acos(std::pow(u(rng), 3.0));
    Vec3 d = spherical_direction(theta, 2 * kPi * u(rng));
    d.z = std::copysign(d.z, z_sign);
    return d;
}

// The lowest and highest vertex of the traversal's surface (n + 1 vertices a side).
std::pair<double, double> vertex_range(const HeightfieldTraversal& t, int n) {
    double lo = 1e300, hi = -1e300;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            lo = std::min(lo, t.vertex(i, j).z), hi = std::max(hi, t.vertex(i, j).z);
    return {lo, hi};
}

std::unique_ptr<Ndf> ndf_of(bool ggx, double alpha) {
    if (ggx) return std::make_unique<Ggx>(alpha);
    return std::make_unique<Beckmann>(alpha);
}
} // namespace

TEST_CASE("hit for hit against Embree on 10^7 pipeline segments, above and below the surface") {
    // Every segment the pipeline gives Embree (bounces, wraps, rays under a dielectric surface)
    // replayed through both backends: same triangle (or one sharing the hit's edge) and t within
    // 1e-5 relative, on all but at most 1e-6 of the segments.
    const BeckersSensor sensor(578);
    const SpecularReflector mirror(FresnelTerm::mirror());
    const DielectricFacet glass(1.5);
    BackendComparison all;
    int k = 0;
    for (int n : {64, 128, 256})
        for (bool ggx : {false, true})
            for (double alpha : {0.1, 0.5, 1.0, 2.0}) {
                const auto ndf = ndf_of(ggx, alpha);
                const HeightField surface = surface_of(*ndf, n, std::uint64_t(7 + k));
                Scene embree(surface, embree_backend());
                const Scene walk(surface, heightfield_backend());
                for (double theta : {0.0, 60.0, 85.0, 89.9}) {
                    const Material& material =
                        (k++ % 2) ? static_cast<const Material&>(glass) : mirror;
                    TraceSettings st;
                    st.rays = theta > 89 ? 1 << 11 : 1 << 14; // grazing: many wraps per ray
                    st.batches = 4;
                    st.seed = std::uint64_t(k);
                    std::vector<float> segments;
                    {
                        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
                        embree.record_segments(&segments);
                        trace_incidence(embree, material, sensor,
                                        spherical_direction(radians(theta), 0.3), st);
                        embree.record_segments(nullptr);
                    }
                    const BackendComparison r = compare_backends(embree, walk, segments);
                    for (const std::string& e : r.examples) MESSAGE(e);
                    all.add(r);
                }
            }
    MESSAGE(all.segments << " segments: " << all.agree << " hits agree (" << all.on_shared_edge
                         << " on a shared edge), " << all.both_missed << " missed by both, "
                         << all.reference_rounding
                         << " where Embree's float arithmetic differs from the exact answer (the "
                            "traversal's does not); "
                         << all.mismatches() << " mismatches; largest relative t difference "
                         << all.max_t_relative);
    CHECK(all.segments >= 10000000);
    CHECK(all.agree > 1000000);
    CHECK(double(all.mismatches()) <= 1e-6 * double(all.segments));
}

TEST_CASE("watertight: rays crossing the surface at its vertices and edges hit it") {
    // A segment from above the surface to below it, through a vertex, an edge (axis-aligned or
    // diagonal) or a cell's inside, crosses the surface: it must hit, at the latest at its end
    // (a ray that only touches a crease from one side may be called either way, so each segment
    // here truly crosses). Border points take vertical rays (a segment starts in the patch).
    const HeightField surface = surface_of(Beckmann(1.0), 32);
    const Scene walk(surface, heightfield_backend());
    const Scene embree(surface, embree_backend());
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    long long crossing = 0, missed = 0, compared = 0;
    const int n = surface.n;
    auto above = [&](const Vec3& p) {
        return p.z - surface.height_at_grid(p.x / surface.spacing, p.y / surface.spacing);
    };
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            for (int where = 0; where < 5; ++where) {
                // A vertex, mid-edge along x, along y, on the diagonal, inside a triangle.
                const double offsets[5][2] = {{0, 0}, {0.5, 0}, {0, 0.5}, {0.5, 0.5}, {0.2, 0.3}};
                const double fx = i + offsets[where][0], fy = j + offsets[where][1];
                const bool border = i == 0 || j == 0 || i == n || j == n;
                if (border && where > 0) continue;
                const Vec3 target{fx * surface.spacing, fy * surface.spacing,
                                  surface.height_at_grid(fx, fy)};
                for (int k = 0; k < (border ? 1 : 8); ++k) {
                    Vec3 d{0, 0, -1};
                    if (k > 0) d = normalize(Vec3{0.6 * u(rng), 0.6 * u(rng), -1});
                    const Vec3 o = target - 0.5 * d, end = target + 0.5 * d;
                    if (above(o) <= 1e-3 || above(end) >= -1e-3) continue; // not a crossing
                    const float of[3] = {float(o.x), float(o.y), float(o.z)};
                    const float df[3] = {float(d.x), float(d.y), float(d.z)};
                    const SegmentHit h = walk.intersect(of, df);
                    ++crossing;
                    if (!std::isfinite(h.t) || h.t > 1.0 + 1e-6) ++missed;
                    const SegmentHit e = embree.intersect(of, df);
                    if (std::isfinite(h.t) && std::isfinite(e.t)) {
                        ++compared;
                        CHECK(h.t == doctest::Approx(e.t).epsilon(1e-4));
                    }
                }
            }
    // Measured: Embree, in float, misses 12 of these 38276 (rays exactly through vertices and
    // edges); the traversal none.
    MESSAGE(crossing << " crossing segments: the traversal missed " << missed << ", Embree "
                     << crossing - compared);
    CHECK(crossing > 5000);
    CHECK(missed == 0);
}

TEST_CASE("Scene::trace gives the same hits, wraps and escapes with both backends") {
    // Random rays from above and below, steep to grazing, through the whole trace (origin rules,
    // wrapping): the same outcome and, for hits, the same point.
    for (double alpha : {0.3, 1.5}) {
        const HeightField surface = surface_of(Beckmann(alpha), 64);
        const Scene walk(surface, heightfield_backend());
        const Scene embree(surface, embree_backend());
        std::mt19937_64 rng(11);
        std::uniform_real_distribution<double> u(0, 1);
        long long rays = 0, differ = 0, hits = 0;
        for (int k = 0; k < 200000; ++k) {
            const bool below = k % 3 == 0;
            const Vec3 d = mostly_grazing(rng, below ? 1 : -1); // towards the surface
            Vec3 o{u(rng) * walk.period(), u(rng) * walk.period(),
                   below ? walk.z_min() - walk.epsilon() : walk.z_max() + walk.epsilon()};
            const SurfaceHit a = embree.trace(o, d, below);
            const SurfaceHit b = walk.trace(o, d, below);
            ++rays;
            bool same = a.kind == b.kind && a.wraps == b.wraps;
            if (same && a.kind == SurfaceHit::hit) {
                ++hits;
                Vec3 gap = a.position - b.position;
                gap.x -= std::round(gap.x / walk.period()) * walk.period();
                gap.y -= std::round(gap.y / walk.period()) * walk.period();
                same = length(gap) < 1e-4 * (1 + a.wraps) && dot(a.normal, b.normal) > 1 - 1e-9;
            }
            if (!same) ++differ;
        }
        CAPTURE(alpha);
        MESSAGE("alpha " << alpha << ": " << rays << " rays, " << hits << " hits, " << differ
                         << " differ");
        CHECK(hits > rays / 2);
        CHECK(double(differ) <= 1e-4 * double(rays));
    }
}

TEST_CASE("a ray meeting the surface within rounding of a side wall hits it with both backends") {
    // Embree sees a ray in float, the wall it leaves through is found in double: a ray meeting a
    // steep facet a few float ulps before the wall reached the wall unhit and past the surface,
    // and re-entered there it passed under the surface (found by the extremes test: GGX
    // alpha = 5, one beam ray in 4096). Rays from above aimed at the surface 0 to 8 ulps (of the
    // patch's coordinates) inside each wall, towards it: every one must hit, and on the facet the
    // traversal (in double) finds.
    const HeightField surface = surface_of(Ggx(5.0), 32, 2);
    const Scene walk(surface, heightfield_backend());
    const Scene embree(surface, embree_backend());
    const HeightfieldTraversal heights(surface);
    const double L = walk.period(), ulp = walk.epsilon();
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(0, 1);
    long long rays = 0, missed = 0, other_facet = 0;
    for (int k = 0; k < 200000; ++k) {
        const int wall = k % 4; // x = 0, x = L, y = 0, y = L
        const double inside = 8 * ulp * u(rng), along = u(rng) * L;
        const double x = wall == 0 ? inside : wall == 1 ? L - inside : along;
        const double y = wall == 2 ? inside : wall == 3 ? L - inside : along;
        const Vec3 target{x, y, heights.height_at(x, y)};
        // Down and towards the wall, steep to grazing.
        Vec3 d = mostly_grazing(rng, -1);
        if (wall < 2)
            d.x = wall == 0 ? -std::abs(d.x) : std::abs(d.x);
        else
            d.y = wall == 2 ? -std::abs(d.y) : std::abs(d.y);
        // From a point above the surface inside the patch, at most one cell back along the ray.
        const double back = std::min(1.0, 0.9 * surface.spacing / std::max(std::abs(d.x), 1e-3));
        const Vec3 o = target - back * d;
        if (o.x < 0 || o.x > L || o.y < 0 || o.y > L || o.z <= heights.height_at(o.x, o.y) + ulp)
            continue;
        ++rays;
        const SurfaceHit a = embree.trace(o, d, false), b = walk.trace(o, d, false);
        missed += (a.kind != SurfaceHit::hit) + (b.kind != SurfaceHit::hit);
        if (a.kind == SurfaceHit::hit && b.kind == SurfaceHit::hit)
            other_facet += dot(a.normal, b.normal) < 1 - 1e-9;
    }
    MESSAGE(rays << " rays at the walls: " << missed << " missed, " << other_facet
                 << " on another facet");
    CHECK(rays > 50000);
    CHECK(missed == 0);
    CHECK(double(other_facet) <= 1e-4 * double(rays));
}

TEST_CASE("rays leaving the surface cross the same walls with both backends") {
    // Rays starting just off the surface and heading away from it (up from above, down from
    // below), many of them grazing: most leave through the top or bottom plane after crossing
    // side walls, some meet the surface again. Both backends must count the same walls (a jump
    // can cross two walls and the plane between them) and report the same outcome.
    for (double alpha : {0.3, 1.5}) {
        const HeightField surface = surface_of(Beckmann(alpha), 64, 3);
        const Scene walk(surface, heightfield_backend());
        const Scene embree(surface, embree_backend());
        const HeightfieldTraversal heights(surface);
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> u(0, 1);
        long long rays = 0, differ = 0, wrapped = 0;
        for (int k = 0; k < 200000; ++k) {
            const bool below = k % 3 == 0;
            const Vec3 d = mostly_grazing(rng, below ? -1 : 1); // away from the surface
            const double x = u(rng) * walk.period(), y = u(rng) * walk.period();
            const double gap = 0.01 + 0.5 * u(rng);
            const Vec3 o{x, y, heights.height_at(x, y) + (below ? -gap : gap)};
            const SurfaceHit a = embree.trace(o, d, below);
            const SurfaceHit b = walk.trace(o, d, below);
            ++rays;
            wrapped += a.wraps > 0;
            if (a.kind != b.kind || a.wraps != b.wraps) ++differ;
        }
        CAPTURE(alpha);
        MESSAGE("alpha " << alpha << ": " << rays << " rays leaving, " << wrapped
                         << " crossed a wall, " << differ << " differ");
        CHECK(wrapped > rays / 10); // the walls are exercised
        CHECK(double(differ) <= 1e-4 * double(rays));
    }
}

TEST_CASE("a beam's rays start where their block is clear, and meet the same facets bit for bit") {
    // Scene::beam_entry lets every ray of a beam skip the stretch its block of origins is known
    // clear over; the walk from there must give exactly what the walk from the top plane gives
    // (kind, point, normal, walls crossed), for steep to grazing beams on rough and smooth
    // surfaces, and skip a good part of the way where rays cross few cells within the relief.
    auto equal = [](const Vec3& p, const Vec3& q) {
        return p.x == q.x && p.y == q.y && p.z == q.z;
    };
    const int per_beam = 10000;
    long long rays = 0, differ = 0, tables = 0;
    for (int n : {64, 256})
        for (int k = 0; k < 5; ++k) {
            const bool ggx = k >= 3;
            const double alpha = std::array<double, 5>{0.1, 0.75, 2.0, 0.3, 1.5}[size_t(k)];
            const HeightField surface = surface_of(*ndf_of(ggx, alpha), n, std::uint64_t(20 + k));
            const Scene walk(surface, heightfield_backend());
            std::mt19937_64 rng(std::uint64_t(100 * n + k));
            std::uniform_real_distribution<double> u(0, 1);
            for (double theta : {0.0, 30.0, 60.0, 75.0, 85.0, 88.0, 89.0, 89.9}) {
                const Vec3 d = -spherical_direction(radians(theta), 2 * kPi * u(rng));
                const BeamEntry beam = walk.beam_entry(d, per_beam);
                CHECK(walk.beam_entry(d, 1).width == 0); // too few rays to pay for a table
                tables += beam.width > 0;
                double skipped = 0, travelled = 0;
                for (int r = 0; r < per_beam; ++r) {
                    const Vec3 o{u(rng) * walk.period(), u(rng) * walk.period(),
                                 walk.z_max() + walk.epsilon()};
                    const SurfaceHit a = walk.trace(o, d);
                    const SurfaceHit b = walk.trace(o, d, false, Scene::kMaxWraps, &beam);
                    ++rays;
                    const bool same = a.kind == b.kind && a.wraps == b.wraps &&
                                      a.reentries == b.reentries && equal(a.position, b.position) &&
                                      equal(a.normal, b.normal);
                    differ += !same;
                    if (beam.width > 0 && a.kind == SurfaceHit::hit) {
                        const int i = std::min(int(o.x / walk.spacing()), n - 1) >> beam.shift;
                        const int j = std::min(int(o.y / walk.spacing()), n - 1) >> beam.shift;
                        skipped += beam.t[size_t(j) * size_t(beam.width) + size_t(i)];
                        travelled += (o.z - a.position.z) / -d.z;
                    }
                }
                CAPTURE(n);
                CAPTURE(alpha);
                CAPTURE(theta);
                // They skip a good part of the way down (measured: 0.31-0.97 of it).
                if (theta <= 60 && beam.width > 0) CHECK(skipped > 0.25 * travelled);
            }
        }
    MESSAGE(rays << " beam rays, " << tables << " beams with a table, " << differ << " differ");
    CHECK(tables >= 40);
    CHECK(differ == 0);
}

TEST_CASE("a grazing beam along a grid axis starts each ray where its row is clear, bit for bit") {
    // Grazing beams along x or y (either way, and a hair off the axis) get per-row max trees
    // instead of the block table: every ray's walk from its row's clear distance must give
    // exactly what the walk from the top plane gives, and rays drifting out of their row (a
    // beam further off the axis) keep the block table.
    auto equal = [](const Vec3& p, const Vec3& q) {
        return p.x == q.x && p.y == q.y && p.z == q.z;
    };
    const int per_beam = 10000; // enough to pay for a table at 256^2
    long long rays = 0, differ = 0, with_rows = 0, hits = 0;
    for (int n : {64, 256})
        for (int k = 0; k < 3; ++k) {
            const double alpha = std::array<double, 3>{0.1, 0.75, 2.0}[size_t(k)];
            const HeightField surface = surface_of(Beckmann(alpha), n, std::uint64_t(40 + k));
            const Scene walk(surface, heightfield_backend());
            std::mt19937_64 rng(std::uint64_t(7 * n + k));
            std::uniform_real_distribution<double> u(0, 1);
            for (double theta : {85.0, 88.0, 89.0, 89.9})
                for (double phi : {0.0, 90.0, 180.0, 270.0, 1e-9, 30.0}) {
                    const Vec3 d = -spherical_direction(radians(theta), radians(phi));
                    const BeamEntry beam = walk.beam_entry(d, per_beam);
                    CAPTURE(n);
                    CAPTURE(alpha);
                    CAPTURE(theta);
                    CAPTURE(phi);
                    if (phi == 30.0) CHECK(beam.row_axis < 0); // drifts across rows
                    with_rows += beam.row_axis >= 0;
                    for (int r = 0; r < per_beam; ++r) {
                        // Origins on grid lines too, where a row's edge is shared.
                        const double x = r % 8 == 0 ? std::floor(u(rng) * n) / n : u(rng);
                        const double y = r % 8 == 1 ? std::floor(u(rng) * n) / n : u(rng);
                        const Vec3 o{x * walk.period(), y * walk.period(),
                                     walk.z_max() + walk.epsilon()};
                        const SurfaceHit a = walk.trace(o, d);
                        const SurfaceHit b = walk.trace(o, d, false, Scene::kMaxWraps, &beam);
                        ++rays, hits += a.kind == SurfaceHit::hit;
                        differ += !(a.kind == b.kind && a.wraps == b.wraps &&
                                    a.reentries == b.reentries && equal(a.position, b.position) &&
                                    equal(a.normal, b.normal));
                    }
                }
        }
    MESSAGE(rays << " grazing beam rays (" << hits << " hits), " << with_rows
                 << " beams with row trees, " << differ << " differ");
    // Along an axis where a ray crosses more than 128 cells within the relief (measured: 80 of
    // the 120 such beams).
    CHECK(with_rows >= 60);
    CHECK(hits > rays / 2);
    CHECK(differ == 0);
}

TEST_CASE("the walk compiled for AVX2 gives the baseline walk's results bit for bit") {
    // Rays from anywhere in the box, either way and many grazing, and a beam's rays with their
    // start table: every field of every result equal.
    if (!HeightfieldTraversal::avx2_supported()) {
        MESSAGE("this processor has no AVX2: only the baseline walk runs here");
        return;
    }
    auto equal = [](const Vec3& p, const Vec3& q) {
        return p.x == q.x && p.y == q.y && p.z == q.z;
    };
    long long rays = 0, differ = 0, hits = 0;
    for (int k = 0; k < 4; ++k) {
        const HeightField surface =
            surface_of(*ndf_of(k % 2 == 1, k < 2 ? 0.3 : 1.5), k < 2 ? 64 : 256, 30 + k);
        HeightfieldTraversal avx2(surface), baseline(surface);
        baseline.use_avx2(false);
        CHECK(avx2.uses_avx2());
        CHECK_FALSE(baseline.uses_avx2());
        const auto [lo, hi] = vertex_range(baseline, surface.n);
        const double top = hi + 1e-3, bottom = lo - 1e-3, L = baseline.period();
        std::mt19937_64 rng(std::uint64_t(40 + k));
        std::uniform_real_distribution<double> u(0, 1);
        const Vec3 beam_d = -spherical_direction(radians(55.0), 0.7);
        const BeamEntry beam = avx2.beam_entry(beam_d, top, 1 << 20);
        for (int r = 0; r < 100000; ++r) {
            const bool from_beam = r % 4 == 0;
            const Vec3 d = from_beam ? beam_d : mostly_grazing(rng, u(rng) < 0.5 ? 1 : -1);
            const Vec3 o{u(rng) * L, u(rng) * L, from_beam ? top : lo + (hi - lo) * u(rng)};
            const TraversalHit a = avx2.trace(o, d, top, bottom, 1000, &beam);
            const TraversalHit b = baseline.trace(o, d, top, bottom, 1000, &beam);
            ++rays;
            hits += a.kind == TraversalHit::hit;
            differ += !(a.kind == b.kind && a.t == b.t && equal(a.position, b.position) &&
                        equal(a.normal, b.normal) && a.cell_x == b.cell_x && a.cell_y == b.cell_y &&
                        a.triangle == b.triangle && a.wraps == b.wraps);
        }
    }
    MESSAGE(rays << " rays, " << hits << " hits, " << differ << " differ");
    CHECK(hits > rays / 4);
    CHECK(differ == 0);
}

TEST_CASE("the ray-parallel walk finds the scalar walk's hits, whatever its lanes") {
    // trace_lanes (SIMD lanes, refilled as rays finish) against the scalar walk, ray by ray:
    // beam rays with their start table, rays from inside the box either way (steep to grazing,
    // so that some go to the scalar walk), on smooth and rough surfaces. Every field equal but
    // where the scalar walk's jumps over clear blocks would round differently: none measured.
    auto equal = [](const Vec3& p, const Vec3& q) {
        return p.x == q.x && p.y == q.y && p.z == q.z;
    };
    CHECK(HeightfieldTraversal::native_lanes() >= 2);
    long long rays = 0, differ = 0, hits = 0;
    for (int k = 0; k < 4; ++k) {
        const HeightField surface =
            surface_of(*ndf_of(k % 2 == 1, k < 2 ? 0.3 : 1.5), k < 2 ? 64 : 256, 50 + k);
        HeightfieldTraversal lanes(surface), scalar(surface);
        scalar.use_lanes(false);
        CHECK(lanes.uses_lanes());
        CHECK_FALSE(scalar.uses_lanes());
        const auto [lo, hi] = vertex_range(scalar, surface.n);
        const double top = hi + 1e-3, bottom = lo - 1e-3, L = scalar.period();
        std::mt19937_64 rng(std::uint64_t(60 + k));
        std::uniform_real_distribution<double> u(0, 1);
        for (double theta : {0.0, 45.0, 70.0, 85.0}) {
            const Vec3 beam_d = -spherical_direction(radians(theta), 0.3 + theta);
            const BeamEntry beam = scalar.beam_entry(beam_d, top, 1 << 20);
            std::vector<LaneRay> in;
            for (int r = 0; r < 20000; ++r) {
                const bool from_beam = r % 2 == 0;
                Vec3 d = beam_d;
                if (!from_beam) {
                    d = r % 3 == 0 ? mostly_grazing(rng, u(rng) < 0.5 ? 1 : -1)
                                   : spherical_direction(std::acos(u(rng)), 2 * kPi * u(rng));
                    if (u(rng) < 0.3) d.z = -d.z;
                }
                const Vec3 o{u(rng) * L, u(rng) * L, from_beam ? top : lo + (hi - lo) * u(rng)};
                in.push_back(LaneRay{o, d, 1000, from_beam ? &beam : nullptr});
            }
            std::vector<TraversalHit> out(in.size());
            lanes.trace_lanes(in.data(), in.size(), top, bottom, out.data());
            for (size_t r = 0; r < in.size(); ++r) {
                const TraversalHit a = out[r];
                const TraversalHit b =
                    scalar.trace(in[r].o, in[r].d, top, bottom, 1000, in[r].beam);
                ++rays;
                hits += a.kind == TraversalHit::hit;
                const bool same = a.kind == b.kind && a.t == b.t && equal(a.position, b.position) &&
                                  equal(a.normal, b.normal) && a.cell_x == b.cell_x &&
                                  a.cell_y == b.cell_y && a.triangle == b.triangle &&
                                  a.wraps == b.wraps;
                differ += !same;
            }
        }
    }
    MESSAGE(rays << " rays, " << hits << " hits, " << differ << " differ");
    CHECK(hits > rays / 4);
    CHECK(differ == 0);
}

TEST_CASE("the ray-parallel walk gives the same bits on every instruction set") {
    // The same stream through every instruction set the lanes are compiled for and this
    // processor has (Highway's run-time dispatch, narrowed one target at a time): 2, 4 or 8
    // lanes, every field of every result equal.
    const HeightField surface = surface_of(Ggx(0.6), 128, 70);
    const HeightfieldTraversal reference(surface);
    const auto [lo, hi] = vertex_range(reference, surface.n);
    const double top = hi + 1e-3, bottom = lo - 1e-3, L = reference.period();
    std::mt19937_64 rng(71);
    std::uniform_real_distribution<double> u(0, 1);
    const Vec3 beam_d = -spherical_direction(radians(63.0), 1.1);
    const BeamEntry beam = reference.beam_entry(beam_d, top, 1 << 20);
    std::vector<LaneRay> in;
    for (int r = 0; r < 40000; ++r) {
        const bool from_beam = r % 2 == 0;
        Vec3 d = from_beam ? beam_d : spherical_direction(std::acos(u(rng)), 2 * kPi * u(rng));
        if (!from_beam && u(rng) < 0.3) d.z = -d.z;
        const Vec3 o{u(rng) * L, u(rng) * L, from_beam ? top : lo + (hi - lo) * u(rng)};
        in.push_back(LaneRay{o, d, 1000, from_beam ? &beam : nullptr});
    }
    std::vector<TraversalHit> expected(in.size());
    reference.trace_lanes(in.data(), in.size(), top, bottom, expected.data());
    const auto targets = HeightfieldTraversal::lane_targets();
    CHECK(targets.size() >= 2);
    for (const auto& [name, bit] : targets) {
        hwy::SetSupportedTargetsForTest(bit);
        const HeightfieldTraversal walk(surface);
        std::vector<TraversalHit> got(in.size());
        walk.trace_lanes(in.data(), in.size(), top, bottom, got.data());
        long long differ = 0;
        for (size_t r = 0; r < in.size(); ++r) {
            const TraversalHit &a = got[r], &b = expected[r];
            differ += !(a.kind == b.kind && a.t == b.t && a.position.x == b.position.x &&
                        a.position.y == b.position.y && a.position.z == b.position.z &&
                        a.normal.x == b.normal.x && a.normal.y == b.normal.y &&
                        a.normal.z == b.normal.z && a.triangle == b.triangle &&
                        a.cell_x == b.cell_x && a.cell_y == b.cell_y && a.wraps == b.wraps);
        }
        MESSAGE(name << ": " << HeightfieldTraversal::native_lanes() << " lanes, " << differ
                     << " of " << in.size() << " differ");
        CHECK(differ == 0);
    }
    hwy::SetSupportedTargetsForTest(0);
}

TEST_CASE("whole runs with either backend agree within their Monte Carlo error, ledgers closed") {
    const BeckersSensor sensor(578);
    const SpecularReflector mirror(FresnelTerm::mirror());
    const DielectricFacet glass(1.5);
    const HeightField surface = surface_of(Ggx(0.8), 128);
    const Scene embree(surface, embree_backend());
    const Scene walk(surface, heightfield_backend());
    for (const Material* m :
         {static_cast<const Material*>(&mirror), static_cast<const Material*>(&glass)})
        for (double theta : {0.0, 60.0, 89.0}) {
            CAPTURE(theta);
            CAPTURE(m->transmits());
            TraceSettings st;
            st.rays = 1 << 17;
            st.orders = 3;
            const Vec3 wi = spherical_direction(radians(theta), 0.4);
            const TraceResult a = trace_incidence(embree, *m, sensor, wi, st);
            const TraceResult b = trace_incidence(walk, *m, sensor, wi, st);
            REQUIRE(a.energy.size() == b.energy.size());
            // Per cell and order: the difference against the two runs' standard errors.
            double worst = 0;
            auto compare = [&](const std::vector<double>& x, const std::vector<double>& sx,
                               const std::vector<double>& y, const std::vector<double>& sy) {
                for (size_t i = 0; i < x.size(); ++i) {
                    const double sigma = std::sqrt(sx[i] * sx[i] + sy[i] * sy[i]);
                    if (sigma > 0)
                        worst = std::max(worst, std::abs(x[i] - y[i]) / sigma);
                    else
                        CHECK(x[i] == doctest::Approx(y[i]).epsilon(1e-12));
                }
            };
            compare(a.energy, a.energy_stderr, b.energy, b.energy_stderr);
            compare(a.transmitted, a.transmitted_stderr, b.transmitted, b.transmitted_stderr);
            CHECK(worst < 5.0);
            for (const TraceResult* r : {&a, &b}) {
                CHECK(r->ledger.lost[0] < 1e-5);
                CHECK(std::abs(r->ledger.unaccounted[0]) < 1e-12);
            }
            CHECK(a.ledger.reflected[0] == doctest::Approx(b.ledger.reflected[0])
                                               .epsilon(5 * a.ledger_stderr.reflected[0] + 1e-12));
        }
}

TEST_CASE("trace.backend chooses the backend, and a bad one is refused by name") {
    const std::string base = "[ndf]\ntype = \"beckmann\"\nalpha = 0.5\n[beam]\ntheta_i = [0]\n";
    // The height field is the default (issue 52: it wins at every size and angle trace_bench
    // looks at); Embree is chosen by name.
    CHECK(&default_trace_backend() == &heightfield_backend());
    CHECK(parse_config(base, "t.toml").cases[0].trace.backend == &default_trace_backend());
    CHECK(parse_config(base + "[trace]\nbackend = \"embree\"\n", "t.toml").cases[0].trace.backend ==
          &embree_backend());
    try {
        parse_config(base + "[trace]\nbackend = \"optix\"\n", "t.toml");
        FAIL("accepted");
    } catch (const ConfigError& e) {
        const std::string what = e.what();
        CHECK(what.find("backend") != std::string::npos);
        CHECK(what.find("heightfield") != std::string::npos);
    }
}
