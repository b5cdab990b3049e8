#include "gonio/model/vcavity_estimator.h"

#include "core/ordered_blocks.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {

struct BlockOutput {
    std::vector<int> bin; // order * cells + cell
    std::vector<double> weight;
    std::vector<double> absorbed, capped, lost;
};

// One V-groove in its cross-section: x along the azimuth a of m, z along n; facet A (normal m)
// spans x in [-1, 0], facet B (normal m') x in [0, 1], both meeting at depth tan(theta_m).
struct Groove {
    Vec3 a, m, mp;
    double s, c;

    explicit Groove(const Vec3& normal) : m(normal) {
        const double sm = std::sqrt(m.x * m.x + m.y * m.y);
        a = sm > 0 ? Vec3{m.x / sm, m.y / sm, 0.0} : Vec3{1.0, 0.0, 0.0};
        s = sm, c = m.z;
        mp = {-m.x, -m.y, m.z};
    }
    // Distance along d from (x, z) to facet A (side 0) or B (side 1); infinity if the ray does not
    // meet its front within the facet's extent. Facet A is the line s x + c z = -s, B -s x + c z =
    // -s.
    double hit(int side, double x, double z, const Vec3& d) const {
        const double dx = dot(d, a), sx = side == 0 ? s : -s;
        const double den = sx * dx + c * d.z; // d.m (or d.m'): the front is met only when < 0
        if (den >= 0) return INFINITY;
        const double t = (-s - sx * x - c * z) / den;
        const double xh = x + t * dx;
        if (t <= 0 || (side == 0 ? (xh < -1 || xh > 0) : (xh < 0 || xh > 1))) return INFINITY;
        return t;
    }
};

} // namespace

TraceResult vcavity_estimate(const Ndf& ndf, const Material& material, const BeckersSensor& sensor,
                             const Vec3& wi, const TraceSettings& st) {
    if (material.transmits())
        throw std::invalid_argument("the V-cavity estimator needs an opaque facet material");
    const auto start = std::chrono::steady_clock::now();
    const int nc = material.channels(), cells = sensor.cell_count(), orders = st.orders + 1;
    const long long paths = std::max(1LL, st.rays);
    const long long blocks = (paths + st.block - 1) / st.block;
    const double power = 1.0 / double(paths);

    auto trace_block = [&](long long b, BlockOutput& o) {
        o.bin.clear(), o.weight.clear();
        o.absorbed.assign(nc, 0.0), o.capped.assign(nc, 0.0), o.lost.assign(nc, 0.0);
        Rng rng{st.seed, st.stream, 0x5643415649545955ull /* "VCAVITY" */, std::uint64_t(b)};
        std::vector<double> w(nc), before(nc);
        const long long first = b * st.block, last = std::min(paths, first + st.block);
        for (long long p = first; p < last; ++p) {
            const double u1 = rng.uniform(), u2 = rng.uniform();
            const Groove g(ndf.sample_m(u1, u2));    // M18 section 3.3: m with pdf D(m) m.n
            double x = 2 * rng.uniform() - 1, z = 0; // uniform over the opening
            Vec3 d = -wi;
            std::fill(w.begin(), w.end(), power);
            int bounces = 0, on = -1; // the facet the path is on (-1: the opening)
            for (;;) {
                const double t0 = on == 0 ? INFINITY : g.hit(0, x, z, d);
                const double t1 = on == 1 ? INFINITY : g.hit(1, x, z, d);
                const int side = t0 <= t1 ? 0 : 1;
                const double t = std::min(t0, t1);
                if (std::isinf(t)) {
                    if (d.z <= 0 || bounces == 0) { // cannot happen in a closed groove
                        for (int k = 0; k < nc; ++k) o.lost[k] += w[k];
                    } else {
                        o.bin.push_back((std::min(bounces, orders) - 1) * cells + sensor.lookup(d));
                        o.weight.insert(o.weight.end(), w.begin(), w.end());
                    }
                    break;
                }
                if (bounces == st.max_bounces) {
                    for (int k = 0; k < nc; ++k) o.capped[k] += w[k];
                    break;
                }
                x += t * dot(d, g.a), z += t * d.z, on = side, ++bounces;
                std::copy(w.begin(), w.end(), before.begin());
                Vec3 next;
                const bool alive =
                    material.scatter(-d, side == 0 ? g.m : g.mp, rng, next, w.data());
                for (int k = 0; k < nc; ++k) o.absorbed[k] += before[k] - (alive ? w[k] : 0.0);
                if (!alive) break;
                d = next;
            }
        }
    };

    TraceResult res;
    res.orders = orders, res.cells = cells, res.channels = nc, res.rays = paths;
    res.energy.assign(size_t(orders) * cells * nc, 0.0);
    EnergyLedger& led = res.ledger;
    led.reflected.assign(size_t(orders) * nc, 0.0);
    led.absorbed.assign(nc, 0.0), led.capped.assign(nc, 0.0), led.lost.assign(nc, 0.0);
    auto merge_block = [&](const BlockOutput& o) {
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
    };
    run_blocks_in_order<BlockOutput>(blocks, trace_block, merge_block);
    led.unaccounted.assign(nc, 1.0);
    for (int k = 0; k < nc; ++k) {
        for (int order = 0; order < orders; ++order)
            led.unaccounted[k] -= led.reflected[size_t(order) * nc + k];
        led.unaccounted[k] -= led.absorbed[k] + led.capped[k] + led.lost[k];
    }
    res.segments = 0;
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return res;
}

} // namespace gonio
