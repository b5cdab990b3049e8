#include "gonio/trace/gonioreflectometer.h"

#include "gonio/trace/batched_run.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

TraceResult trace_incidence(const Scene& scene, const Material& material,
                            const BeckersSensor& sensor, const Vec3& wi, const TraceSettings& st) {
    const int nc = material.channels(), cells = sensor.cell_count();
    const int orders = st.orders + 1;
    const long long B = std::max(1, st.batches);
    // Every batch is a beam of its own, stratified on an S x S grid over the patch.
    const long long wanted = (std::max(1LL, st.rays) + B - 1) / B;
    const long long side = (long long)std::ceil(std::sqrt(double(wanted)));
    const double L = scene.period(), eps = scene.epsilon();
    const Vec3 down = -wi;
    const bool transmits = material.transmits();
    // Every batch's beam rays start on the top plane along `down`: they may start lower.
    const BeamEntry beam = scene.beam_entry(down, std::max(1LL, st.rays));

    // A block's rays are traced a generation at a time: every live ray's next segment in one
    // stream (Scene::trace_stream), so that a backend can trace them side by side; then each
    // segment's end is handled in the rays' order (the random numbers are drawn in that order,
    // so the result does not depend on how the backend schedules its rays).
    auto trace_block = [&](long long id, long long first, long long last, BlockOutput& o) {
        o.clear(nc);
        long long segments = 0; // counted locally: neighbouring blocks may share a cache line
        Rng rng{st.seed, st.stream, std::uint64_t(id)};
        const size_t count = size_t(last - first);
        // The working arrays, per thread, kept from block to block (their allocation and growth
        // showed in perf, ~2 % of a mirror's run at 1024^2, theta_i 60 deg; the saving was within
        // the runs' noise).
        struct Work {
            std::vector<StreamRay> rays, next_rays;
            std::vector<SurfaceHit> hits;
            std::vector<int> bounces, next_bounces;
            std::vector<double> w, next_w; // each ray's power, per channel
        };
        thread_local Work work;
        std::vector<StreamRay>&rays = work.rays, &next_rays = work.next_rays;
        std::vector<SurfaceHit>& hits = work.hits;
        std::vector<int>&bounces = work.bounces, &next_bounces = work.next_bounces;
        std::vector<double>&w = work.w, &next_w = work.next_w;
        rays.resize(count), hits.resize(count);
        bounces.assign(count, 0), w.assign(count * size_t(nc), 1.0);
        std::vector<double> before(static_cast<size_t>(nc));
        next_rays.reserve(count), next_bounces.reserve(count), next_w.reserve(w.size());
        // Every ray leaves at most once.
        o.bin.reserve(count), o.exit.reserve(count), o.weight.reserve(count * size_t(nc));
        // A ray's nc weights onto the end of v (vector::insert of a range costs ~60 instructions
        // for one channel: callgrind, 4 % of a mirror's pipeline).
        auto append = [nc](std::vector<double>& v, const double* from) {
            for (int k = 0; k < nc; ++k) v.push_back(from[k]);
        };
        // Ray r of the batch's beam lies in grid cell (r mod S, r div S); the cell is stepped
        // rather than divided out per ray.
        long long cx = first % side, cy = first / side;
        const double cell = L / double(side);
        for (size_t r = 0; r < count; ++r) {
            const double x = (double(cx) + rng.uniform()) * cell;
            const double y = (double(cy) + rng.uniform()) * cell;
            rays[r] = StreamRay{{x, y, scene.z_max() + eps}, down, false, &beam};
            if (++cx == side) cx = 0, ++cy;
        }
        while (!rays.empty()) {
            hits.resize(rays.size());
            scene.trace_stream(rays.data(), rays.size(), Scene::kMaxWraps, hits.data());
            next_rays.clear(), next_bounces.clear(), next_w.clear();
            for (size_t r = 0; r < rays.size(); ++r) {
                const SurfaceHit& h = hits[r];
                const Vec3 dir = rays[r].dir;
                const bool below = rays[r].below;
                double* wr = w.data() + r * size_t(nc);
                int ray_bounces = bounces[r];
                segments += h.wraps + 1;
                // The ray's remaining power ends in a ledger entry.
                auto spend = [&](std::vector<double>& entry) {
                    for (int k = 0; k < nc; ++k) entry[size_t(k)] += wr[k];
                };
                if (h.kind == SurfaceHit::escaped_up || h.kind == SurfaceHit::escaped_down) {
                    // A ray leaves for good only upwards from above and downwards from below; and
                    // a beam aimed down cannot leave before a bounce. Anything else is a failure.
                    const bool up = h.kind == SurfaceHit::escaped_up;
                    if (ray_bounces == 0 || up == below) {
                        spend(o.lost);
                        continue;
                    }
                    const int order = std::min(ray_bounces, orders) - 1;
                    o.bin.push_back(up ? order : orders + order);
                    o.exit.push_back(dir);
                    append(o.weight, wr);
                    continue;
                }
                if (h.kind != SurfaceHit::hit) { // wrapped without end
                    spend(o.lost);
                    continue;
                }
                if (ray_bounces == st.max_bounces) {
                    spend(o.capped);
                    continue;
                }
                ++ray_bounces;
                std::copy(wr, wr + nc, before.begin());
                Vec3 next;
                const bool alive = material.scatter(-dir, h.normal, rng, next, wr);
                for (int k = 0; k < nc; ++k)
                    o.absorbed[size_t(k)] += before[size_t(k)] - (alive ? wr[k] : 0.0);
                if (!alive) continue;
                // Unit already: reflection and refraction keep the length, sampling returns unit.
                // Leave the facet on the side the ray goes, by Scene::epsilon() (one float ulp).
                const double along = dot(next, h.normal);
                const bool next_below = transmits ? along < 0 : below;
                next_rays.push_back(StreamRay{h.position + (along >= 0 ? eps : -eps) * h.normal,
                                              next, next_below, nullptr});
                next_bounces.push_back(ray_bounces);
                append(next_w, wr);
            }
            rays.swap(next_rays), bounces.swap(next_bounces), w.swap(next_w);
        }
        o.segments = segments;
        // Bin the block's exits in one pass: the sensor's tables stay in cache (between bounces
        // the traversal evicts them) and the lookups overlap.
        for (size_t e = 0; e < o.bin.size(); ++e)
            o.bin[e] = o.bin[e] * cells + (o.bin[e] < orders ? sensor.lookup(o.exit[e])
                                                             : sensor.lookup_lower(o.exit[e]));
    };

    BatchTally tally(int(B), orders, cells, nc, transmits);
    return run_batched(st, side * side, tally, sensor, trace_block);
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
    return concatenate_channels(r);
}

TraceResult concatenate_channels(const std::vector<TraceResult>& r) {
    if (r.size() == 1) return r[0];
    TraceResult res;
    res.orders = r[0].orders, res.cells = r[0].cells, res.batches = r[0].batches;
    // Rays, rounds and error: those of the part that needed the most (a target is met by each).
    for (const TraceResult& p : r) {
        res.channels += p.channels, res.segments += p.segments, res.seconds += p.seconds;
        if (p.rays >= res.rays) res.rays = p.rays, res.rounds = p.rounds, res.stop = p.stop;
        res.achieved_error = std::max(res.achieved_error, p.achieved_error);
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
    for (auto map : {&TraceResult::energy, &TraceResult::transmitted, &TraceResult::energy_stderr,
                     &TraceResult::transmitted_stderr, &TraceResult::energy_batches,
                     &TraceResult::transmitted_batches})
        res.*map = concat([map](const TraceResult& p) -> const auto& { return p.*map; });
    for (auto side : {&TraceResult::energy_sums, &TraceResult::transmitted_sums})
        for (auto sum : {&OrderSums::l1, &OrderSums::l2plus, &OrderSums::linf})
            (res.*side).*sum = concat(
                [ side, sum ](const TraceResult& p) -> const auto& { return (p.*side).*sum; });
    for (auto ledger :
         {&TraceResult::ledger, &TraceResult::ledger_stderr, &TraceResult::ledger_batches})
        for (auto entry :
             {&EnergyLedger::reflected, &EnergyLedger::transmitted, &EnergyLedger::absorbed,
              &EnergyLedger::capped, &EnergyLedger::lost, &EnergyLedger::unaccounted})
            (res.*ledger).*entry = concat([ ledger, entry ](const TraceResult& p) -> const auto& {
                return (p.*ledger).*entry;
            });
    return res;
}

} // namespace gonio

namespace gonio {

TraceResult combine_batch_shards(const std::vector<TraceResult>& parts) {
    if (parts.empty()) throw std::invalid_argument("combine_batch_shards: no parts");
    TraceResult res = parts[0];
    const size_t n = parts.size();
    const int B = res.batches;
    res.rays = 0, res.segments = 0, res.seconds = 0;
    for (const TraceResult& p : parts) {
        if (p.batches != B || p.energy_batches.size() != res.energy_batches.size())
            throw std::invalid_argument("combine_batch_shards: parts of different traces");
        res.rays += p.rays, res.segments += p.segments;
        res.seconds = std::max(res.seconds, p.seconds);
    }
    // Batch b from the part that traced it.
    auto take = [&](auto get) {
        std::vector<double>& out = get(res);
        if (out.empty()) return;
        const size_t per = out.size() / size_t(B);
        for (int b = 0; b < B; ++b) {
            const std::vector<double>& from = get(const_cast<TraceResult&>(parts[size_t(b) % n]));
            std::copy(from.begin() + long(size_t(b) * per),
                      from.begin() + long(size_t(b + 1) * per),
                      out.begin() + long(size_t(b) * per));
        }
    };
    take([](TraceResult& t) -> std::vector<double>& { return t.energy_batches; });
    take([](TraceResult& t) -> std::vector<double>& { return t.transmitted_batches; });
    for (auto entry : {&EnergyLedger::reflected, &EnergyLedger::transmitted,
                       &EnergyLedger::absorbed, &EnergyLedger::capped, &EnergyLedger::lost})
        take([entry](TraceResult& t) -> std::vector<double>& { return t.ledger_batches.*entry; });
    BatchTally::complete(res, !res.transmitted_batches.empty());
    return res;
}

} // namespace gonio
