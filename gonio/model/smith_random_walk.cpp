#include "gonio/model/smith_random_walk.h"

#include "gonio/model/model_kind.h"
#include "gonio/trace/batched_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace gonio {

namespace {

// The height of the next intersection of a path at height h (as u = C1(h), uniform heights on
// [-1, 1]) going in direction w, the surface seen from above; false when the path escapes.
// Going up it escapes with probability G1(w, h) = C1(h)^Lambda(w), else meets the surface at
// C1(h') = C1(h) / (1 - U)^(1 / Lambda(w)); going down it always meets it, at
// C1(h') = C1(h) (1 - U)^(1 / (1 + Lambda(-w))) [H16 section 4, the free-path distribution].
bool next_height(const Ndf& ndf, const Vec3& w, double& u, double U) {
    if (w.z >= 0) {
        const double lambda = ndf.lambda(w); // infinite along the horizon: met where it is
        if (lambda <= 0) return false;       // straight up: nothing above
        if (U >= 1 - std::pow(u, lambda)) return false;
        u = std::min(1.0, u / std::pow(1 - U, 1 / lambda));
        return true;
    }
    u *= std::pow(1 - U, 1 / (1 + ndf.lambda(-w)));
    return true;
}

} // namespace

Vec3 sample_visible_any(const Ndf& ndf, const Vec3& v, Rng& rng) {
    if (v.z > 0) {
        const double u1 = rng.uniform(), u2 = rng.uniform();
        return ndf.sample_visible(v, u1, u2);
    }
    // max(0, v.m) <= max(0, v'.m) for every m above the plane, v' = v mirrored above it: accept a
    // normal visible from v' with probability v.m / v'.m. The rate is Lambda(-v) / (1 +
    // Lambda(v')); a path going nearly straight up, where it is small, rarely meets a facet.
    const Vec3 up = normalize(Vec3{v.x, v.y, std::max(-v.z, 1e-12)});
    Vec3 m{0, 0, 1};
    for (int tries = 0; tries < 1 << 24; ++tries) {
        const double u1 = rng.uniform(), u2 = rng.uniform();
        m = ndf.sample_visible(up, u1, u2);
        if (rng.uniform() * dot(up, m) < dot(v, m)) break;
    }
    return m;
}

TraceResult smith_random_walk(const Ndf& ndf, const Material& material, const BeckersSensor& sensor,
                              const Vec3& wi, const TraceSettings& st) {
    const int nc = material.channels(), cells = sensor.cell_count(), orders = st.orders + 1;
    const bool transmits = material.transmits();
    const long long B = std::max(1, st.batches);
    const long long per_batch = (std::max(1LL, st.rays) + B - 1) / B;

    auto trace_block = [&](long long id, long long first, long long last, BlockOutput& o) {
        o.clear(nc);
        Rng rng{st.seed, st.stream, 0x534d49544857414cull /* "SMITHWAL" */, std::uint64_t(id)};
        std::vector<double> w(nc), before(nc);
        for (long long p = first; p < last; ++p) {
            Vec3 d = -wi;        // where the path goes
            double u = 1;        // C1 of its height: it starts above every facet
            bool outside = true; // above the surface (a dielectric's inside is below it)
            std::fill(w.begin(), w.end(), 1.0);
            int bounces = 0;
            for (;;) {
                // Inside a dielectric the walk sees the surface from above with every direction
                // and height flipped (H16 section 5.3).
                const Vec3 df = outside ? d : -d;
                double uf = outside ? u : 1 - u;
                if (!next_height(ndf, df, uf, rng.uniform())) {
                    const int order = std::min(bounces, orders) - 1;
                    o.bin.push_back(outside ? order * cells + sensor.lookup(d)
                                            : (orders + order) * cells + sensor.lookup_lower(d));
                    o.weight.insert(o.weight.end(), w.begin(), w.end());
                    break;
                }
                u = outside ? uf : 1 - uf;
                if (bounces == st.max_bounces) {
                    for (int k = 0; k < nc; ++k) o.capped[k] += w[k];
                    break;
                }
                ++bounces;
                // The facet, seen from where the path comes (H16 section 5: the visible normals);
                // its upward normal is m in either frame, met from below inside a dielectric.
                const Vec3 m = sample_visible_any(ndf, -df, rng);
                std::copy(w.begin(), w.end(), before.begin());
                Vec3 next;
                const bool alive = material.scatter(-d, m, rng, next, w.data());
                for (int k = 0; k < nc; ++k) o.absorbed[k] += before[k] - (alive ? w[k] : 0.0);
                if (!alive) break;
                d = next;
                if (transmits) outside = dot(d, m) > 0;
            }
        }
    };

    BatchTally tally(int(B), orders, cells, nc, transmits);
    return run_batched(st, per_batch, tally, sensor, trace_block);
}

} // namespace gonio

namespace gonio {
namespace {
const Key kPaths = Key::integer("heitz16_rays", {1, 1e12}, "heitz16: paths per incidence")
                       .note_default("`trace.rays`");

// The random walk as a model of the case: every order, held against simulated L-infinity (and its
// orders 2 and up against L2+), with its batches for the errors and orders 1, 2, 3+ for the file.
// A dispersive dielectric's channels are walked apart, each on its own streams.
class SmithRandomWalkModel final : public CellModel {
  public:
    SmithRandomWalkModel(std::shared_ptr<const Ndf> ndf,
                         std::vector<std::unique_ptr<Material>> parts, long long rays,
                         int max_bounces)
        : ndf_(std::move(ndf)), parts_(std::move(parts)), rays_(rays), max_bounces_(max_bounces) {}

    ModelIncidence evaluate(const Vec3& wi, const BeckersSensor& sensor, std::uint64_t seed,
                            std::uint64_t stream) const override {
        const auto start = std::chrono::steady_clock::now();
        TraceSettings st;
        st.rays = rays_;
        st.orders = ModelIncidence::kOrderBins - 1; // orders 1, 2, then 3 and up
        st.max_bounces = max_bounces_;
        st.seed = seed;
        std::vector<TraceResult> parts;
        for (size_t p = 0; p < parts_.size(); ++p) {
            st.stream = parts_.size() == 1 ? stream : stream ^ (std::uint64_t(p + 1) << 56);
            parts.push_back(smith_random_walk(*ndf_, *parts_[p], sensor, wi, st));
        }
        ModelIncidence m = monte_carlo_incidence(concatenate_channels(parts));
        m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return m;
    }

  private:
    std::shared_ptr<const Ndf> ndf_;
    std::vector<std::unique_ptr<Material>> parts_;
    long long rays_;
    int max_bounces_;
};
} // namespace

const ModelKind& heitz16_model_kind() {
    static const ModelKind k{
        "heitz16",
        "Smith random walk, every order, any facet material [Heitz et al. 2016]",
        {kPaths},
        [](TableReader& r, const ModelContext& c) {
            ModelChoice m;
            m.name = "heitz16";
            m.compared_with = ModelTarget::linf;
            m.monte_carlo = true;
            const long long rays = r.integer(kPaths.name, kPaths.range, c.trace_rays);
            m.description = "Smith random walk, every order [Heitz et al. 2016], " +
                            std::to_string(rays) + " paths per incidence";
            m.build = [ndf = c.ndf, parts = c.facets.parts, max_bounces = c.max_bounces,
                       rays](const HeightField*) -> std::unique_ptr<CellModel> {
                return std::make_unique<SmithRandomWalkModel>(ndf, parts(), rays, max_bounces);
            };
            return m;
        }};
    return k;
}
} // namespace gonio
