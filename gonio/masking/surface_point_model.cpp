// The decomposition of simulated L1 against Model L1 (gonio masking's models): single scattering
// written as F D_s(h) G(i, o, h) / (4 |i.n| |o.n|) with the surface's own facet NDF D_s and three
// choices of G, each estimated over points drawn uniformly by area on the case's surfaces (a
// point's facet normal is distributed as D_s(m) dm; an ensemble's points are spread over the
// surfaces the incidence was traced on). For a mirror facet the exit is o = reflect(i,
// m), and the energy into a cell is
//   E_cell = (A_micro / A_macro) E_points[ chi(o in cell) <i, m>+ F(i.m) G ] / cos theta_i,
// the h-integral of Model L1 [R19 Eq. 2] after the change of variables dw_o = 4 <i, h> dw_h. With
//   smith_measured_ndf: G = Smith's G2 (the case's masking form) from Lambda_s, the Lambda of D_s;
//   measured_g1: G = G1(i, m) G1(o, m), measured: the visibility towards i of one point times the
//     visibility towards o of another point whose normal falls in the same fine bin (independent
//     given m: the product of the two masking probabilities);
//   measured: G = the joint visibility V(i) V(o) of the same point, the surface's G2(i, o, m).
// The chain Model L1 -> smith_measured_ndf -> measured_g1 -> measured splits simulated L1 - Model
// L1 into the NDF's fidelity, the facet-dependence of masking and the correlation of masking with
// shadowing; `measured` and simulated L1 estimate the same quantity of the same surface.
#include "core/batch_means.h"
#include "core/parallel.h"
#include "core/random.h"
#include "gonio/masking/facet_sampler.h"
#include "gonio/model/model_kind.h"
#include "gonio/trace/scene.h"
#include "heightfield/ndf/ndf_table.h"
#include "heightfield/ndf/tabulated_ndf.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

namespace gonio {

namespace {

enum class PointG { smith_measured_ndf, measured_g1, measured };

const Key kPoints = Key::integer("surface_points", {1024, 1e12},
                                 "smith_measured_ndf, measured_g1, measured: facet points per "
                                 "incidence")
                        .note_default("`trace.rays`");

constexpr int kBatches = 16;
// measured_g1: a point's partner shares its normal's bin; bins hold 4 points on average, at most
// 16 384 bins. Points are drawn and paired in chunks of at most 2^20 (memory: O(chunk)).
constexpr long long kChunk = 1 << 20;
int pairing_bins(long long points) {
    return int(std::clamp(points / 4, 64LL, 16384LL));
}

// One surface of the case: its facet sampler and its facet NDF (Lambda_s).
struct PointSurface {
    HeightField surface;
    FacetSampler sampler; // holds a reference to `surface`: not copied, not moved
    TabulatedNdf facets;  // D_s as a table (kFacetTable): its Lambda for smith_measured_ndf

    explicit PointSurface(const HeightField& s)
        : surface(s), sampler(surface),
          facets(facet_ndf_table(s, kFacetTable.theta_intervals, kFacetTable.phi_count),
                 "the surface", "height_map") {}
    PointSurface(const PointSurface&) = delete;
    PointSurface& operator=(const PointSurface&) = delete;
};

// The next point in the same bin (cyclically; itself when alone in it).
std::vector<long long> partners(const std::vector<Vec3>& normal, const BeckersSensor& bins) {
    const size_t n = normal.size();
    std::vector<int> bin(n);
    for (size_t k = 0; k < n; ++k) bin[k] = bins.lookup(normal[k]);
    std::vector<long long> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](long long a, long long b) { return bin[size_t(a)] < bin[size_t(b)]; });
    std::vector<long long> partner(n);
    size_t first = 0;
    for (size_t k = 0; k < n; ++k) {
        if (k > 0 && bin[size_t(order[k])] != bin[size_t(order[k - 1])]) first = k;
        const bool last = k + 1 == n || bin[size_t(order[k + 1])] != bin[size_t(order[k])];
        partner[size_t(order[k])] = last ? order[first] : order[k + 1];
    }
    return partner;
}

class SurfacePointModel final : public CellModel {
  public:
    SurfacePointModel(PointG g, const HeightField& first, const TraceBackendKind& backend,
                      FresnelTerm fresnel, MaskingForm masking, long long points)
        : g_(g), backend_(backend), fresnel_(std::move(fresnel)), masking_(masking),
          points_(points) {
        add_surface(first);
    }

    void add_surface(const HeightField& s) override {
        surfaces_.push_back(std::make_unique<PointSurface>(s));
    }

    ModelIncidence evaluate(const Vec3& wi, const BeckersSensor& sensor, std::uint64_t seed,
                            std::uint64_t stream) const override {
        return evaluate_on(wi, sensor, seed, stream, 1);
    }

    // One surface: 16 batches of its points. An ensemble: one batch per surface (its share of the
    // points), as the simulation's ensembles batch by surface, so that the errors include the
    // surfaces' spread.
    ModelIncidence evaluate_on(const Vec3& wi, const BeckersSensor& sensor, std::uint64_t seed,
                               std::uint64_t stream, int surfaces) const override {
        const auto start = std::chrono::steady_clock::now();
        const int nc = fresnel_.channels(), cells = sensor.cell_count();
        const int B = surfaces > 1 ? surfaces : kBatches;
        const long long per_batch = (points_ + B - 1) / B;
        std::vector<double> batches(size_t(B) * cells * nc, 0.0);
        // One surface: its scene shared by the batches; an ensemble: each batch builds its own
        // surface's scene (at most one per thread alive).
        std::unique_ptr<Scene> shared;
        if (surfaces == 1) shared = std::make_unique<Scene>(surfaces_[0]->surface, backend_);
        parallel_for<int>(0, B, [&](int b) {
            const int r = surfaces > 1 ? b : 0;
            const PointSurface& ps = *surfaces_[size_t(r)];
            std::unique_ptr<Scene> own;
            if (!shared) own = std::make_unique<Scene>(ps.surface, backend_);
            const Scene& scene = shared ? *shared : *own;
            Rng rng{seed, stream, 0x73706d6full /* "spmo" */, std::uint64_t(b)};
            const double lambda_i = ps.facets.lambda(wi);
            const double eps = scene.epsilon();
            const double scale = ps.sampler.area_ratio() / (wi.z * double(per_batch));
            double* out = &batches[size_t(b) * cells * nc];
            double F[kMaxChannels];
            std::vector<Vec3> pos, normal;
            std::vector<long long> partner;
            for (long long from = 0; from < per_batch; from += kChunk) {
                const long long n = std::min(kChunk, per_batch - from);
                pos.resize(size_t(n)), normal.resize(size_t(n));
                for (size_t k = 0; k < pos.size(); ++k) ps.sampler.draw(rng, pos[k], normal[k]);
                // measured_g1: each point's partner is the next point of the chunk in its bin.
                if (g_ == PointG::measured_g1)
                    partner = partners(normal, BeckersSensor(pairing_bins(n)));
                auto sees = [&](long long at, const Vec3& w) {
                    if (dot(w, normal[size_t(at)]) <= 0) return false;
                    return scene.trace(pos[size_t(at)] + eps * normal[size_t(at)], w).kind ==
                           SurfaceHit::escaped_up;
                };
                for (long long k = 0; k < n; ++k) {
                    const Vec3& m = normal[size_t(k)];
                    const double im = dot(wi, m);
                    if (im <= 0) continue;
                    const Vec3 o = 2.0 * im * m - wi; // mirror reflection about the facet
                    if (o.z <= 0) continue;           // into the surface: not single scattering
                    double g = 0;
                    switch (g_) {
                    case PointG::smith_measured_ndf: // R19 Eq. 9 (or the case's form), Lambda_s
                        g = smith_g2(lambda_i, ps.facets.lambda(o), wi, o, masking_);
                        break;
                    case PointG::measured_g1:
                        g = sees(k, wi) && sees(partner[size_t(k)], o) ? 1.0 : 0.0;
                        break;
                    case PointG::measured:
                        g = sees(k, wi) && sees(k, o) ? 1.0 : 0.0;
                        break;
                    }
                    if (g == 0) continue;
                    fresnel_.eval(im, F);
                    double* cell = out + size_t(sensor.lookup(o)) * nc;
                    for (int c = 0; c < nc; ++c) cell[c] += scale * im * F[c] * g;
                }
            }
        });
        ModelIncidence r;
        r.batches = B;
        r.energy.assign(size_t(cells) * nc, 0.0);
        for (int b = 0; b < B; ++b)
            for (size_t k = 0; k < r.energy.size(); ++k)
                r.energy[k] += batches[size_t(b) * r.energy.size() + k] / B;
        r.energy_batches = std::move(batches);
        // Albedo batches: each batch's cells summed.
        std::vector<double> albedo_batches(size_t(B) * nc, 0.0);
        for (int b = 0; b < B; ++b)
            for (int c = 0; c < cells; ++c)
                for (int k = 0; k < nc; ++k)
                    albedo_batches[size_t(b) * nc + k] +=
                        r.energy_batches[(size_t(b) * cells + c) * nc + k];
        r.albedo_stderr = batch_stderr(albedo_batches, B);
        // Single scattering only: order 1 is everything.
        r.l1_energy = r.energy;
        r.l1_albedo.assign(size_t(nc), 0.0);
        for (int c = 0; c < cells; ++c)
            for (int k = 0; k < nc; ++k) r.l1_albedo[size_t(k)] += r.energy[size_t(c) * nc + k];
        r.l2_albedo.assign(size_t(nc), 0.0);
        r.l2plus_albedo.assign(size_t(nc), 0.0);
        r.l1_energy_batches = r.energy_batches;
        r.order_albedo.assign(size_t(ModelIncidence::kOrderBins * nc), 0.0);
        r.order_albedo_stderr = r.order_albedo;
        std::copy(r.l1_albedo.begin(), r.l1_albedo.end(), r.order_albedo.begin());
        std::copy(r.albedo_stderr.begin(), r.albedo_stderr.end(), r.order_albedo_stderr.begin());
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return r;
    }

  private:
    PointG g_;
    const TraceBackendKind& backend_;
    FresnelTerm fresnel_;
    MaskingForm masking_;
    long long points_;
    std::vector<std::unique_ptr<PointSurface>> surfaces_;
};

ModelChoice point_model(PointG g, const char* name, const std::string& what, TableReader& r,
                        const ModelContext& c) {
    if (c.facets.diffuse)
        r.fail("models", std::string("\"") + name + "\" is a specular model; for " + c.facets.type +
                             " facets use \"il\"");
    ModelChoice m;
    m.name = name;
    m.compared_with = ModelTarget::l1;
    m.needs_surface = true;
    m.monte_carlo = true;
    const long long points =
        r.integer(kPoints.name, kPoints.range, std::max<long long>(c.trace_rays, kPoints.range.lo));
    if (g == PointG::smith_measured_ndf && c.masking == MaskingForm::v_cavity)
        r.fail("masking",
               "smith_measured_ndf uses a Smith form of G2; \"v-cavity\" is not one "
               "(choose height-correlated, uncorrelated or height-direction-correlated)");
    m.description =
        what + ", over " + std::to_string(points) + " points of the case's surfaces per incidence";
    m.build = [g, points, fresnel = c.facets.fresnel, masking = c.masking,
               backend = c.backend](const HeightField* surface) -> std::unique_ptr<CellModel> {
        return std::make_unique<SurfacePointModel>(g, *surface, *backend, fresnel, masking, points);
    };
    return m;
}

} // namespace

const ModelKind& smith_measured_ndf_model_kind() {
    static const ModelKind k{
        "smith_measured_ndf",
        "Model L1 on the surface's own facet NDF D_s, Smith G2 from its Lambda [R19 Eq. 2, 9]",
        {kPoints},
        [](TableReader& r, const ModelContext& c) {
            return point_model(PointG::smith_measured_ndf, "smith_measured_ndf",
                               "single scattering with D_s and Smith's G2 from Lambda_s", r, c);
        }};
    return k;
}

const ModelKind& measured_g1_model_kind() {
    static const ModelKind k{
        "measured_g1",
        "single scattering with D_s and the measured G1(i, m) G1(o, m) (masking and shadowing "
        "uncorrelated)",
        {},
        [](TableReader& r, const ModelContext& c) {
            return point_model(PointG::measured_g1, "measured_g1",
                               "single scattering with D_s and the measured G1(i, m) G1(o, m)", r,
                               c);
        }};
    return k;
}

const ModelKind& measured_model_kind() {
    static const ModelKind k{
        "measured",
        "single scattering with D_s and the measured joint G2(i, o, m)",
        {},
        [](TableReader& r, const ModelContext& c) {
            return point_model(PointG::measured, "measured",
                               "single scattering with D_s and the measured joint G2(i, o, m)", r,
                               c);
        }};
    return k;
}

} // namespace gonio
