#include "gonio/trace/gonioreflectometer.h"

#include "core/ordered_blocks.h"

#include <chrono>
#include <cmath>

namespace gonio {

namespace {

// What one block of rays produced: its exits, in ray order, and its ledger sums. Blocks are
// merged in block order, so the sums do not depend on which thread ran which block.
struct BlockOutput {
    std::vector<int> bin;       // order * cells + cell, + orders * cells when transmitted
    std::vector<Vec3> exit;     // exit directions, binned once the block is traced
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
    const bool transmits = material.transmits();

    auto trace_block = [&](long long b, BlockOutput& o) {
        o.bin.clear(), o.exit.clear(), o.weight.clear();
        long long segments = 0; // counted locally: neighbouring blocks may share a cache line
        o.absorbed.assign(nc, 0.0), o.capped.assign(nc, 0.0), o.lost.assign(nc, 0.0);
        Rng rng{st.seed, st.stream, std::uint64_t(b)};
        std::vector<double> w(nc), before(nc);
        const long long first = b * st.block, last = std::min(rays, first + st.block);
        // Stratified beam: one ray per cell of an S x S grid over the patch, ray r in cell
        // (r mod S, r div S); the cell is stepped rather than divided out per ray.
        long long cx = first % side, cy = first / side;
        const double cell = L / double(side);
        for (long long r = first; r < last; ++r) {
            const double x = (double(cx) + rng.uniform()) * cell;
            const double y = (double(cy) + rng.uniform()) * cell;
            Vec3 origin{x, y, scene.z_max() + eps};
            Vec3 dir = down;
            std::fill(w.begin(), w.end(), power);
            int bounces = 0;
            bool below = false; // travelling under the surface (transmissive materials only)
            // The ray's remaining power ends in a ledger entry.
            auto spend = [&](std::vector<double>& entry) {
                for (int k = 0; k < nc; ++k) entry[k] += w[k];
            };
            for (;;) {
                const SurfaceHit h = scene.trace(origin, dir, below);
                segments += h.wraps + 1;
                if (h.kind == SurfaceHit::escaped_up || h.kind == SurfaceHit::escaped_down) {
                    // A ray leaves for good only upwards from above and downwards from below; and
                    // a beam aimed down cannot leave before a bounce. Anything else is a failure.
                    const bool up = h.kind == SurfaceHit::escaped_up;
                    if (bounces == 0 || up == below) {
                        spend(o.lost);
                        break;
                    }
                    const int order = std::min(bounces, orders) - 1;
                    o.bin.push_back(up ? order : orders + order);
                    o.exit.push_back(dir);
                    o.weight.insert(o.weight.end(), w.begin(), w.end());
                    break;
                }
                if (h.kind != SurfaceHit::hit) { // wrapped without end
                    spend(o.lost);
                    break;
                }
                if (bounces == st.max_bounces) {
                    spend(o.capped);
                    break;
                }
                ++bounces;
                for (int k = 0; k < nc; ++k) before[k] = w[k];
                Vec3 next;
                const bool alive = material.scatter(-dir, h.normal, rng, next, w.data());
                for (int k = 0; k < nc; ++k) o.absorbed[k] += before[k] - (alive ? w[k] : 0.0);
                if (!alive) break;
                // Unit already: reflection and refraction keep the length, sampling returns unit.
                dir = next;
                // Leave the facet on the side the ray goes, by Scene::epsilon() (one float ulp).
                const double along = dot(dir, h.normal);
                if (transmits) below = along < 0;
                origin = h.position + (along >= 0 ? eps : -eps) * h.normal;
            }
            if (++cx == side) cx = 0, ++cy;
        }
        o.segments = segments;
        // Bin the block's exits in one pass: the sensor's tables stay in cache (between bounces
        // Embree's traversal evicts them) and the lookups overlap.
        for (size_t e = 0; e < o.bin.size(); ++e)
            o.bin[e] = o.bin[e] * cells + (o.bin[e] < orders ? sensor.lookup(o.exit[e])
                                                             : sensor.lookup_lower(o.exit[e]));
    };

    TraceResult res;
    res.orders = orders, res.cells = cells, res.channels = nc, res.rays = rays;
    res.energy.assign(size_t(orders) * cells * nc, 0.0);
    if (transmits) res.transmitted.assign(size_t(orders) * cells * nc, 0.0);
    EnergyLedger& led = res.ledger;
    led.reflected.assign(size_t(orders) * nc, 0.0);
    if (transmits) led.transmitted.assign(size_t(orders) * nc, 0.0);
    led.absorbed.assign(nc, 0.0), led.capped.assign(nc, 0.0), led.lost.assign(nc, 0.0);
    auto merge_block = [&](const BlockOutput& o) {
        for (size_t e = 0; e < o.bin.size(); ++e) {
            const bool up = o.bin[e] < orders * cells;
            const int bin = up ? o.bin[e] : o.bin[e] - orders * cells, order = bin / cells;
            double* energy = (up ? res.energy : res.transmitted).data();
            double* sum = (up ? led.reflected : led.transmitted).data();
            for (int k = 0; k < nc; ++k) {
                energy[size_t(bin) * nc + k] += o.weight[e * nc + k];
                sum[size_t(order) * nc + k] += o.weight[e * nc + k];
            }
        }
        for (int k = 0; k < nc; ++k)
            led.absorbed[k] += o.absorbed[k], led.capped[k] += o.capped[k],
                led.lost[k] += o.lost[k];
        res.segments += o.segments;
    };
    run_blocks_in_order<BlockOutput>(blocks, trace_block, merge_block);
    led.unaccounted.assign(nc, 1.0);
    for (int k = 0; k < nc; ++k) {
        for (int order = 0; order < orders; ++order) {
            led.unaccounted[k] -= led.reflected[size_t(order) * nc + k];
            if (transmits) led.unaccounted[k] -= led.transmitted[size_t(order) * nc + k];
        }
        led.unaccounted[k] -= led.absorbed[k] + led.capped[k] + led.lost[k];
    }
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return res;
}

TraceResult trace_incidence(const Scene& scene, const std::vector<const Material*>& parts,
                            const BeckersSensor& sensor, const Vec3& wi, const TraceSettings& st) {
    if (parts.size() == 1) return trace_incidence(scene, *parts[0], sensor, wi, st);
    std::vector<TraceResult> r;
    for (size_t p = 0; p < parts.size(); ++p) {
        TraceSettings part = st;
        part.stream ^= std::uint64_t(p + 1) << 56; // streams apart from every case and incidence
        r.push_back(trace_incidence(scene, *parts[p], sensor, wi, part));
    }
    TraceResult res;
    res.orders = r[0].orders, res.cells = r[0].cells, res.rays = r[0].rays;
    for (const TraceResult& p : r) {
        res.channels += p.channels, res.segments += p.segments, res.seconds += p.seconds;
    }
    // [outer][channel] arrays: concatenate the parts' channels within every outer index.
    auto concat = [&](auto get) {
        std::vector<double> out;
        const size_t outer = get(r[0]).size() / size_t(r[0].channels);
        out.reserve(outer * size_t(res.channels));
        for (size_t i = 0; i < outer; ++i)
            for (const TraceResult& p : r) {
                const std::vector<double>& v = get(p);
                out.insert(out.end(), v.begin() + i * p.channels, v.begin() + (i + 1) * p.channels);
            }
        return out;
    };
    res.energy = concat([](const TraceResult& p) -> const auto& { return p.energy; });
    res.transmitted = concat([](const TraceResult& p) -> const auto& { return p.transmitted; });
    for (auto entry :
         {&EnergyLedger::reflected, &EnergyLedger::transmitted, &EnergyLedger::absorbed,
          &EnergyLedger::capped, &EnergyLedger::lost, &EnergyLedger::unaccounted})
        res.ledger.*entry =
            concat([entry](const TraceResult& p) -> const auto& { return p.ledger.*entry; });
    return res;
}

} // namespace gonio
