#include "gonio/model/vcavity_estimator.h"

#include "core/batch_means.h"
#include "gonio/model/model_kind.h"
#include "gonio/trace/batched_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {

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
    const int nc = material.channels(), cells = sensor.cell_count(), orders = st.orders + 1;
    const long long B = std::max(1, st.batches);
    const long long per_batch = (std::max(1LL, st.rays) + B - 1) / B;

    auto trace_block = [&](long long id, long long first, long long last, BlockOutput& o) {
        o.clear(nc);
        Rng rng{st.seed, st.stream, 0x5643415649545955ull /* "VCAVITY" */, std::uint64_t(id)};
        std::vector<double> w(nc), before(nc);
        for (long long p = first; p < last; ++p) {
            const double u1 = rng.uniform(), u2 = rng.uniform();
            const Groove g(ndf.sample_m(u1, u2));    // M18 section 3.3: m with pdf D(m) m.n
            double x = 2 * rng.uniform() - 1, z = 0; // uniform over the opening
            Vec3 d = -wi;
            std::fill(w.begin(), w.end(), 1.0); // divided by the batch's paths when finished
            int bounces = 0, on = -1;           // the facet the path is on (-1: the opening)
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

    BatchTally tally(int(B), orders, cells, nc, false);
    return run_batched(st, per_batch, tally, sensor, trace_block);
}

} // namespace gonio

namespace gonio {
namespace {
const Key kRays = Key::integer("vcavity_rays", {1, 1e12}, "vcavity: paths per incidence")
                      .note_default("`trace.rays`");

// The estimator as a model of the case: every order, held against simulated L-infinity, with
// its batches for the comparison's errors and its orders 1, 2 and 2+ for the file.
class VCavityModel final : public CellModel {
  public:
    VCavityModel(std::shared_ptr<const Ndf> ndf, std::unique_ptr<Material> facet, long long rays,
                 int max_bounces)
        : ndf_(std::move(ndf)), facet_(std::move(facet)), rays_(rays), max_bounces_(max_bounces) {}

    ModelIncidence evaluate(const Vec3& wi, const BeckersSensor& sensor, std::uint64_t seed,
                            std::uint64_t stream) const override {
        const auto start = std::chrono::steady_clock::now();
        TraceSettings st;
        st.rays = rays_;
        st.orders = 2; // f1, f2, then every higher order together [M18 Fig. 9]
        st.max_bounces = max_bounces_;
        st.seed = seed, st.stream = stream;
        ModelIncidence m = monte_carlo_incidence(vcavity_estimate(*ndf_, *facet_, sensor, wi, st));
        m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return m;
    }

  private:
    std::shared_ptr<const Ndf> ndf_;
    std::unique_ptr<Material> facet_;
    long long rays_;
    int max_bounces_;
};
} // namespace

// A Monte Carlo estimator of every order, held against simulated L-infinity; opaque facets only.
const ModelKind& vcavity_model_kind() {
    static const ModelKind k{
        "vcavity",
        "V-cavity multiple scattering, every order [M18 section 3.3]",
        {kRays},
        [](TableReader& r, const ModelContext& c) {
            if (c.facets.transmits)
                r.fail("models", "\"vcavity\" follows paths inside opaque V-grooves; " +
                                     c.facets.type + " facets transmit");
            ModelChoice m;
            m.name = "vcavity";
            m.compared_with = ModelTarget::linf;
            m.monte_carlo = true;
            const long long rays = r.integer(kRays.name, kRays.range, c.trace_rays);
            m.description = "V-cavity multiple scattering, every order [M18 section 3.3], " +
                            std::to_string(rays) + " paths per incidence";
            m.build = [ndf = c.ndf, parts = c.facets.parts, max_bounces = c.max_bounces,
                       rays](const HeightField*) -> std::unique_ptr<CellModel> {
                return std::make_unique<VCavityModel>(ndf, std::move(parts()[0]), rays,
                                                      max_bounces);
            };
            return m;
        }};
    return k;
}
} // namespace gonio
