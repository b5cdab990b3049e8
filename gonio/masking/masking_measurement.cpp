#include "gonio/masking/masking_measurement.h"

#include "core/check.h"
#include "core/parallel.h"
#include "core/random.h"
#include "gonio/masking/facet_sampler.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

namespace gonio {

void MaskingCounts::add(const MaskingCounts& o) {
    if (points == 0) {
        *this = o;
        return;
    }
    GONIO_CHECK(o.g1_front.size() == g1_front.size() && o.g2_front.size() == g2_front.size());
    area_ratio =
        (area_ratio * double(points) + o.area_ratio * double(o.points)) / double(points + o.points);
    points += o.points;
    auto sum = [](auto& a, const auto& b) {
        for (size_t k = 0; k < a.size(); ++k) a[k] += b[k];
    };
    sum(g1_front, o.g1_front), sum(g1_visible, o.g1_visible);
    sum(g1h_front, o.g1h_front), sum(g1h_visible, o.g1h_visible);
    sum(furnace_sum, o.furnace_sum), sum(furnace_sum2, o.furnace_sum2);
    sum(projected_sum, o.projected_sum), sum(projected_sum2, o.projected_sum2);
    sum(g2_front, o.g2_front), sum(g2_visible, o.g2_visible);
}

MaskingDirections masking_directions(const MaskingGrid& g) {
    MaskingDirections d;
    for (double t : g.theta_o_deg)
        for (double p : g.phi_o_deg) d.w.push_back(spherical_direction(radians(t), radians(p)));
    d.g2_theta_deg = g.g2_theta_o_deg;
    for (double t : g.theta_i_deg) d.g2_theta_deg.push_back(t); // the retro direction's polar angle
    std::sort(d.g2_theta_deg.begin(), d.g2_theta_deg.end());
    d.g2_theta_deg.erase(std::unique(d.g2_theta_deg.begin(), d.g2_theta_deg.end()),
                         d.g2_theta_deg.end());
    for (double ti : g.theta_i_deg)
        for (double pi : g.phi_i_deg) {
            d.wi.push_back(spherical_direction(radians(ti), radians(pi)));
            std::vector<Vec3> wo;
            for (double t : d.g2_theta_deg)
                for (double dp : g.g2_dphi_deg)
                    wo.push_back(spherical_direction(radians(t), radians(pi + dp)));
            d.wo.push_back(std::move(wo));
        }
    return d;
}

namespace {

// A point on the facets, with its facet's normal.
struct FacetPoint {
    Vec3 position, normal;
};

} // namespace

MaskingCounts measure_masking(const HeightField& s, const Scene& scene, const MaskingGrid& grid,
                              long long points, long long g2_points, std::uint64_t seed,
                              const MaskingProgress& progress) {
    const MaskingDirections dirs = masking_directions(grid);
    const BeckersSensor bins(grid.normal_bins);
    const size_t nw = dirs.w.size(), nb = size_t(grid.normal_bins), nh = size_t(grid.height_bins);
    const size_t ni = dirs.wi.size(), nwo = ni ? dirs.wo[0].size() : 0;
    MaskingCounts c;
    c.points = points;
    const FacetSampler sampler(s);
    c.area_ratio = sampler.area_ratio();

    // The points, drawn in blocks with their own streams (the same points whatever the threads).
    constexpr long long kBlock = 4096;
    const long long blocks = (points + kBlock - 1) / kBlock;
    std::vector<FacetPoint> pts(static_cast<size_t>(points));
    parallel_for<long long>(0, blocks, [&](long long b) {
        Rng rng{seed, 0x6d61736bull /* "mask" */, std::uint64_t(b)};
        for (long long k = b * kBlock; k < std::min(points, (b + 1) * kBlock); ++k)
            sampler.draw(rng, pts[size_t(k)].position, pts[size_t(k)].normal);
    });
    // Height quantiles.
    {
        std::vector<double> h(pts.size());
        for (size_t k = 0; k < pts.size(); ++k) h[k] = pts[k].position.z;
        std::sort(h.begin(), h.end());
        c.height_edges.resize(nh + 1);
        for (size_t q = 0; q <= nh; ++q)
            c.height_edges[q] = h.empty() ? 0 : h[std::min(h.size() - 1, q * h.size() / nh)];
        c.height_edges.back() = std::nextafter(h.empty() ? 0 : h.back(), HUGE_VAL);
    }

    c.g1_front.assign(nw * nb, 0), c.g1_visible.assign(nw * nb, 0);
    c.g1h_front.assign(nw * nh, 0), c.g1h_visible.assign(nw * nh, 0);
    c.g2_front.assign(ni * nwo * nb, 0), c.g2_visible.assign(ni * nwo * nb, 0);
    std::vector<double> block_sum(size_t(blocks) * nw, 0.0), block_sum2(size_t(blocks) * nw, 0.0),
        block_projected(size_t(blocks) * nw, 0.0), block_projected2(size_t(blocks) * nw, 0.0);
    std::mutex merge;
    std::atomic<long long> done{0};
    const double eps = scene.epsilon();
    auto sees = [&](const FacetPoint& f, const Vec3& w) {
        const SurfaceHit h = scene.trace(f.position + eps * f.normal, w);
        return h.kind == SurfaceHit::escaped_up;
    };
    parallel_for<long long>(0, blocks, [&](long long b) {
        const bool g2 = b * kBlock < g2_points; // G2's counters only where it is measured
        std::vector<long long> f1(nw * nb, 0), v1(nw * nb, 0), fh(nw * nh, 0), vh(nw * nh, 0),
            f2(g2 ? ni * nwo * nb : 0, 0), v2(f2.size(), 0);
        std::vector<char> seen_i(ni);
        for (long long k = b * kBlock; k < std::min(points, (b + 1) * kBlock); ++k) {
            const FacetPoint& f = pts[size_t(k)];
            const size_t bin = size_t(bins.lookup(f.normal));
            const size_t hq = size_t(std::upper_bound(c.height_edges.begin() + 1,
                                                      c.height_edges.end() - 1, f.position.z) -
                                     (c.height_edges.begin() + 1));
            for (size_t w = 0; w < nw; ++w) {
                const double wm = dot(dirs.w[w], f.normal);
                if (wm <= 0) continue;
                const bool v = sees(f, dirs.w[w]);
                ++f1[w * nb + bin], ++fh[w * nh + hq];
                block_projected[size_t(b) * nw + w] += c.area_ratio * wm;
                block_projected2[size_t(b) * nw + w] += c.area_ratio * wm * c.area_ratio * wm;
                if (v) {
                    ++v1[w * nb + bin], ++vh[w * nh + hq];
                    const double x =
                        c.area_ratio * wm; // Heitz 2014 section 3: the mean is cos theta_w
                    block_sum[size_t(b) * nw + w] += x;
                    block_sum2[size_t(b) * nw + w] += x * x;
                }
            }
            for (size_t i = 0; i < (k < g2_points ? ni : 0); ++i) {
                const bool front_i = dot(dirs.wi[i], f.normal) > 0;
                seen_i[i] = front_i && sees(f, dirs.wi[i]);
                if (!front_i) continue;
                for (size_t o = 0; o < nwo; ++o) {
                    const Vec3& wo = dirs.wo[i][o];
                    if (dot(wo, f.normal) <= 0) continue;
                    const size_t at = (i * nwo + o) * nb + bin;
                    ++f2[at];
                    if (seen_i[i] && sees(f, wo)) ++v2[at];
                }
            }
        }
        {
            std::lock_guard<std::mutex> lock(merge); // integer sums: exact in any order
            for (size_t k = 0; k < f1.size(); ++k) c.g1_front[k] += f1[k], c.g1_visible[k] += v1[k];
            for (size_t k = 0; k < fh.size(); ++k)
                c.g1h_front[k] += fh[k], c.g1h_visible[k] += vh[k];
            for (size_t k = 0; k < f2.size(); ++k) c.g2_front[k] += f2[k], c.g2_visible[k] += v2[k];
        }
        if (progress) progress(double(++done) / double(blocks));
    });
    // The furnace's floating sums, block by block in order.
    c.furnace_sum.assign(nw, 0.0), c.furnace_sum2.assign(nw, 0.0), c.projected_sum.assign(nw, 0.0);
    c.projected_sum2.assign(nw, 0.0);
    for (long long b = 0; b < blocks; ++b)
        for (size_t w = 0; w < nw; ++w) {
            c.furnace_sum[w] += block_sum[size_t(b) * nw + w];
            c.furnace_sum2[w] += block_sum2[size_t(b) * nw + w];
            c.projected_sum[w] += block_projected[size_t(b) * nw + w];
            c.projected_sum2[w] += block_projected2[size_t(b) * nw + w];
        }
    return c;
}

} // namespace gonio
