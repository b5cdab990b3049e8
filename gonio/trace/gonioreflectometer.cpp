#include "gonio/trace/gonioreflectometer.h"

#include <chrono>
#include <cmath>
#include <tbb/parallel_for.h>

namespace gonio {

namespace {

// What one block of rays produced: its exits, in ray order, and its ledger sums. Blocks are
// merged in block order, so the sums do not depend on which thread ran which block.
struct BlockOutput {
    std::vector<int> bin;       // order * cells + cell
    std::vector<double> weight; // channels per exit
    std::vector<double> absorbed, capped, lost;
    long long segments = 0;
};

} // namespace

TraceResult trace_incidence(const Scene& scene, const Material& material,
                            const BeckersSensor& sensor, const Vec3& wi, const TraceSettings& st) {
    const auto start = std::chrono::steady_clock::now();
    const int nc = material.channels(), cells = sensor.cell_count();
    const int orders = st.orders + 1;
    const long long side = (long long)std::ceil(std::sqrt(double(std::max(1LL, st.rays))));
    const long long rays = side * side;
    const long long blocks = (rays + st.block - 1) / st.block;
    const double power = 1.0 / double(rays);
    const double L = scene.period(), eps = scene.epsilon();
    const Vec3 down = -wi;

    std::vector<BlockOutput> out(blocks);
    tbb::parallel_for((long long)0, blocks, [&](long long b) {
        BlockOutput& o = out[b];
        o.absorbed.assign(nc, 0.0), o.capped.assign(nc, 0.0), o.lost.assign(nc, 0.0);
        Rng rng{st.seed, st.stream, std::uint64_t(b)};
        std::vector<double> w(nc), before(nc);
        const long long first = b * st.block, last = std::min(rays, first + st.block);
        for (long long r = first; r < last; ++r) {
            // Stratified beam: one ray per cell of an S x S grid over the patch.
            const double x = (double(r % side) + rng.uniform()) / double(side) * L;
            const double y = (double(r / side) + rng.uniform()) / double(side) * L;
            Vec3 origin{x, y, scene.z_max() + eps};
            Vec3 dir = down;
            std::fill(w.begin(), w.end(), power);
            int bounces = 0;
            // The ray's remaining power ends in a ledger entry.
            auto spend = [&](std::vector<double>& entry) {
                for (int k = 0; k < nc; ++k) entry[k] += w[k];
            };
            for (;;) {
                const SurfaceHit h = scene.trace(origin, dir);
                o.segments += h.wraps + 1;
                if (h.kind == SurfaceHit::escaped_up) {
                    // A beam aimed down cannot leave before a bounce; keep the ledger honest.
                    if (bounces == 0) {
                        spend(o.lost);
                        break;
                    }
                    const int order = std::min(bounces, orders) - 1;
                    o.bin.push_back(order * cells + sensor.lookup(dir));
                    o.weight.insert(o.weight.end(), w.begin(), w.end());
                    break;
                }
                if (h.kind != SurfaceHit::hit) { // down through an opaque surface, or endless
                    spend(o.lost);
                    break;
                }
                if (bounces == st.max_bounces) {
                    spend(o.capped);
                    break;
                }
                ++bounces;
                before = w;
                Vec3 next;
                const bool alive = material.scatter(-dir, h.normal, rng, next, w.data());
                for (int k = 0; k < nc; ++k) o.absorbed[k] += before[k] - (alive ? w[k] : 0.0);
                if (!alive) break;
                dir = normalize(next);
                // Leave the facet on the side the ray goes, by Scene::epsilon() (one float ulp).
                origin = h.position + (dot(dir, h.normal) >= 0 ? eps : -eps) * h.normal;
            }
        }
    });

    TraceResult res;
    res.orders = orders, res.cells = cells, res.channels = nc, res.rays = rays;
    res.energy.assign(size_t(orders) * cells * nc, 0.0);
    EnergyLedger& led = res.ledger;
    led.reflected.assign(size_t(orders) * nc, 0.0);
    led.absorbed.assign(nc, 0.0), led.capped.assign(nc, 0.0), led.lost.assign(nc, 0.0);
    for (const BlockOutput& o : out) { // block order: deterministic
        for (size_t e = 0; e < o.bin.size(); ++e) {
            const int order = o.bin[e] / cells;
            for (int k = 0; k < nc; ++k) {
                res.energy[size_t(o.bin[e]) * nc + k] += o.weight[e * nc + k];
                led.reflected[size_t(order) * nc + k] += o.weight[e * nc + k];
            }
        }
        for (int k = 0; k < nc; ++k)
            led.absorbed[k] += o.absorbed[k], led.capped[k] += o.capped[k],
                led.lost[k] += o.lost[k];
        res.segments += o.segments;
    }
    led.unaccounted.assign(nc, 1.0);
    for (int k = 0; k < nc; ++k) {
        for (int order = 0; order < orders; ++order)
            led.unaccounted[k] -= led.reflected[size_t(order) * nc + k];
        led.unaccounted[k] -= led.absorbed[k] + led.capped[k] + led.lost[k];
    }
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return res;
}

} // namespace gonio
