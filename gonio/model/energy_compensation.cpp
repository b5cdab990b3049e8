#include "gonio/model/energy_compensation.h"

#include "core/catmull_rom.h"
#include "core/check.h"
#include "core/parallel.h"
#include "core/quadrature.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/microfacet_model.h"
#include "gonio/trace/gonioreflectometer.h"
#include "gonio/trace/scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace gonio {

namespace {
constexpr int kAzimuths = 4; // an anisotropic E is averaged over 0, 45, 90 and 135 degrees

// Nodes evenly spaced in theta from the normal to the horizon (theta_k = k pi / (2 (n - 1))),
// where E varies evenly; the last is evaluated just above the horizon (E's grazing limit). A
// table that stopped short of it would put a kink in the integrand, which the cells' quadrature
// near the horizon would not see.
double node_step() {
    return 0.5 * kPi / (AlbedoTable::kNodes - 1);
}
double node_mu(int k) {
    return std::cos(std::min(k * node_step(), radians(89.95)));
}

} // namespace

AlbedoTable AlbedoTable::of_nodes(std::vector<double> e) {
    GONIO_CHECK(int(e.size()) == kNodes);
    AlbedoTable t;
    t.e = std::move(e);
    t.padded_ = t.e;
    t.padded_.insert(t.padded_.begin(), t.e[1]);
    // E_avg = int 2 E(theta) cos(theta) sin(theta) dtheta over the interpolant, interval by
    // interval (each a cubic: 8 Gauss-Legendre points leave only the round-off).
    const GaussLegendre& g = gauss_legendre(8);
    const double h = node_step();
    for (int k = 0; k + 1 < AlbedoTable::kNodes; ++k)
        for (size_t j = 0; j < g.nodes.size(); ++j) {
            const double theta = (k + 0.5 * (g.nodes[j] + 1)) * h;
            t.average += g.weights[j] * 0.5 * h * t.at(std::cos(theta)) * std::sin(2 * theta);
        }
    return t;
}

double AlbedoTable::at(double mu) const {
    // Catmull-Rom in theta (node k at x = k + 1 of `padded`, the last at the horizon). E is
    // even in theta: the ghost node before theta = 0 mirrors node 1, so that E has no kink there
    // (a kink in theta is a square root in mu, which the cells' quadrature would not see).
    return catmull_rom(padded_, 1 + std::acos(std::clamp(mu, 0.0, 1.0)) / node_step());
}

AlbedoTable AlbedoTable::smith(const Ndf& ndf, MaskingForm masking, const CellQuadrature& q) {
    const MicrofacetModel white(ndf, FresnelTerm::mirror(), masking);
    // The albedo is a sum over the cells, each integrated adaptively to q's tolerance: few large
    // cells cost least (the lobe's refinement is the same whatever their number).
    const BeckersSensor sensor(145);
    const int azimuths = ndf.isotropic() ? 1 : kAzimuths;
    CellQuadrature table_q = q;
    table_q.rel_tol = std::max(q.rel_tol, 1e-5); // per cell; the sum's error averages out
    std::vector<double> e(size_t(kNodes * azimuths), 0.0);
    parallel_for(0, kNodes * azimuths, [&](long long job) {
        const int k = int(job / azimuths), a = int(job % azimuths);
        const double mu = node_mu(k);
        const Vec3 wi = spherical_direction(std::acos(mu), kPi * a / azimuths);
        double sum = 0;
        for (double x : model_cell_energy(white, wi, sensor, table_q)) sum += x;
        e[size_t(job)] = sum; // summed over the azimuths below, in order
    });
    std::vector<double> mean(kNodes, 0.0);
    for (int k = 0; k < kNodes; ++k)
        for (int a = 0; a < azimuths; ++a)
            mean[size_t(k)] += e[size_t(k * azimuths + a)] / azimuths;
    return of_nodes(mean);
}

AlbedoTable AlbedoTable::surface(const HeightField& surface, const TraceBackendKind& backend,
                                 long long rays) {
    const Scene scene(surface, backend);
    const SpecularReflector mirror(FresnelTerm::mirror());
    const BeckersSensor sensor(145);
    std::vector<double> e(kNodes, 0.0);
    for (int k = 0; k < kNodes; ++k)
        for (int a = 0; a < kAzimuths; ++a) {
            TraceSettings st;
            st.rays = std::max(1LL, rays / kAzimuths);
            st.orders = 1;
            st.seed = 0x45544142; // fixed streams: the table is a function of the surface
            st.stream = std::uint64_t(k * kAzimuths + a);
            st.backend = &backend;
            const Vec3 wi = spherical_direction(std::acos(node_mu(k)), kPi * a / kAzimuths);
            e[size_t(k)] +=
                trace_incidence(scene, mirror, sensor, wi, st).ledger.reflected[0] / kAzimuths;
        }
    return of_nodes(e);
}

std::vector<double> average_fresnel(const FresnelTerm& fresnel) {
    const GaussLegendre& g = gauss_legendre(64);
    const int nc = fresnel.channels();
    std::vector<double> avg(size_t(nc), 0.0), f(static_cast<size_t>(nc), 0.0);
    for (size_t j = 0; j < g.nodes.size(); ++j) {
        const double mu = 0.5 * (g.nodes[j] + 1); // [-1, 1] -> [0, 1]
        fresnel.eval(mu, f.data());
        for (int c = 0; c < nc; ++c)
            avg[size_t(c)] += g.weights[j] * f[size_t(c)] * mu; // dmu = dx / 2
    }
    return avg;
}

namespace {

// The Kulla-Conty lobe times F_ms per channel: smooth, a function of mu_i and mu_o alone.
class KullaContyLobe final : public BrdfModel {
  public:
    KullaContyLobe(std::shared_ptr<const AlbedoTable> e, std::vector<double> scale)
        : e_(std::move(e)), scale_(std::move(scale)) {}
    int channels() const override { return int(scale_.size()); }
    void eval_cosine(const Vec3& i, const Vec3& o, double* out) const override {
        // (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg)) [Kulla & Conty 2017], times cos theta_o.
        const bool above = i.z > 0 && o.z > 0 && e_->average < 1;
        const double lobe =
            above ? (1 - e_->at(i.z)) * (1 - e_->at(o.z)) * o.z / (kPi * (1 - e_->average)) : 0.0;
        for (size_t c = 0; c < scale_.size(); ++c) out[c] = lobe * scale_[c];
    }
    double narrowest_feature() const override { return INFINITY; }
    double widest_feature() const override { return INFINITY; }

  private:
    std::shared_ptr<const AlbedoTable> e_;
    std::vector<double> scale_;
};

class CompensatedModel final : public CellModel {
  public:
    CompensatedModel(Compensation kind, std::shared_ptr<const Ndf> ndf, const FresnelTerm& fresnel,
                     MaskingForm masking, const CellQuadrature& quadrature,
                     std::shared_ptr<const AlbedoTable> albedo)
        : ndf_(std::move(ndf)), l1_(*ndf_, fresnel, masking), quadrature_(quadrature),
          albedo_(std::move(albedo)) {
        const int nc = fresnel.channels();
        if (kind == Compensation::kulla_conty) {
            // F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) [Kulla & Conty 2017]
            const double ea = albedo_->average;
            std::vector<double> scale;
            for (double fa : average_fresnel(fresnel))
                scale.push_back(fa * fa * ea / (1 - fa * (1 - ea)));
            lobe_ = std::make_unique<KullaContyLobe>(albedo_, std::move(scale));
        } else {
            f0_.resize(size_t(nc));
            fresnel.eval(1.0, f0_.data());
        }
    }

    ModelIncidence evaluate(const Vec3& wi, const BeckersSensor& sensor, std::uint64_t,
                            std::uint64_t) const override {
        const auto start = std::chrono::steady_clock::now();
        ModelIncidence m;
        m.l1_energy = model_cell_energy(l1_, wi, sensor, quadrature_, &m.relative_tolerance);
        m.energy = m.l1_energy;
        const size_t nc = size_t(l1_.channels());
        if (lobe_) {
            double reached = 0;
            const std::vector<double> ms =
                model_cell_energy(*lobe_, wi, sensor, quadrature_, &reached);
            for (size_t i = 0; i < ms.size(); ++i) m.energy[i] += ms[i];
            m.relative_tolerance = std::max(m.relative_tolerance, reached);
        } else {
            // f_ss (1 + F0 (1 - E) / E) [Turquin 2019], E at the incidence.
            const double e = albedo_->at(wi.z);
            for (size_t i = 0; i < m.energy.size(); ++i)
                m.energy[i] *= e > 0 ? 1 + f0_[i % nc] * (1 - e) / e : 1.0;
        }
        m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return m;
    }

  private:
    std::shared_ptr<const Ndf> ndf_;
    MicrofacetModel l1_;
    CellQuadrature quadrature_;
    std::shared_ptr<const AlbedoTable> albedo_;
    std::unique_ptr<KullaContyLobe> lobe_;
    std::vector<double> f0_;
};

} // namespace

std::unique_ptr<CellModel> compensated_model(Compensation kind, std::shared_ptr<const Ndf> ndf,
                                             const FresnelTerm& fresnel, MaskingForm masking,
                                             const CellQuadrature& quadrature,
                                             std::shared_ptr<const AlbedoTable> albedo) {
    GONIO_CHECK(albedo && int(albedo->e.size()) == AlbedoTable::kNodes);
    return std::make_unique<CompensatedModel>(kind, std::move(ndf), fresnel, masking, quadrature,
                                              std::move(albedo));
}

} // namespace gonio

#include "gonio/model/model_kind.h"

#include <mutex>

namespace gonio {
namespace {

// Where a compensation takes E(mu) from.
enum class AlbedoSource { smith, surface };
} // namespace
template <>
struct EnumNames<AlbedoSource> {
    static constexpr const char* what = "albedo table";
    static constexpr const char* names[] = {"smith", "surface"};
};
namespace {

struct CompensationKeys {
    Key albedo, rays;
};
CompensationKeys keys_of(const std::string& name) {
    return {Key::string(name + "_albedo", enum_names<AlbedoSource>(),
                        name + ": E(mu) from Smith's model of the case's NDF, or from the "
                               "explicit surface's single-scattering albedo (traced)")
                .fallback("smith"),
            Key::integer(name + "_rays", {1024, 1e10},
                         name + ": rays per node of the surface's E(mu) table (91 nodes)")
                .fallback(65536.0)};
}

// A case's Smith E(mu) table, made once whichever model and unit needs it first (kulla_conty and
// turquin of one case share it): keyed by the case's distribution (held weakly: a table outlives
// no case), its masking and quadrature. (A surface's table is made by each model that asks.)
std::shared_ptr<const AlbedoTable> smith_table(const std::shared_ptr<const Ndf>& ndf,
                                               MaskingForm masking, const CellQuadrature& q) {
    struct Entry {
        std::weak_ptr<const Ndf> ndf;
        MaskingForm masking;
        double tolerance;
        std::shared_ptr<const AlbedoTable> table;
    };
    static std::mutex lock;
    static std::vector<Entry> entries;
    std::lock_guard<std::mutex> guard(lock); // tables are made one at a time (each is parallel)
    entries.erase(std::remove_if(entries.begin(), entries.end(),
                                 [](const Entry& e) { return e.ndf.expired(); }),
                  entries.end());
    for (const Entry& e : entries)
        if (e.ndf.lock() == ndf && e.masking == masking && e.tolerance == q.rel_tol) return e.table;
    auto table = std::make_shared<const AlbedoTable>(AlbedoTable::smith(*ndf, masking, q));
    entries.push_back({ndf, masking, q.rel_tol, table});
    return table;
}

ModelChoice read_compensation(TableReader& r, const ModelContext& c, Compensation kind,
                              const std::string& name, const CompensationKeys& keys,
                              const std::string& what) {
    if (c.facets.diffuse || c.facets.transmits)
        r.fail("models", "\"" + name +
                             "\" compensates Model L1 of opaque specular facets (mirror, "
                             "conductor, schlick); " +
                             c.facets.type + " facets: use \"heitz16\"");
    ModelChoice m;
    m.name = name;
    m.compared_with = ModelTarget::linf;
    const AlbedoSource source = enum_named<AlbedoSource>(r.string(keys.albedo));
    const long long rays = r.integer(keys.rays);
    m.needs_surface = source == AlbedoSource::surface;
    m.description = "Model L1 + " + what + ", E(mu) from " +
                    (source == AlbedoSource::smith
                         ? "Smith's model of the NDF"
                         : "the explicit surface (" + std::to_string(rays) + " rays a node)");
    m.build = [=, ndf = c.ndf, fresnel = c.facets.fresnel, masking = c.masking,
               quadrature = c.quadrature,
               backend = c.backend](const HeightField* surface) -> std::unique_ptr<CellModel> {
        return compensated_model(kind, ndf, fresnel, masking, quadrature,
                                 source == AlbedoSource::smith
                                     ? smith_table(ndf, masking, quadrature)
                                     : std::make_shared<const AlbedoTable>(
                                           AlbedoTable::surface(*surface, *backend, rays)));
    };
    return m;
}
} // namespace

const ModelKind& kulla_conty_model_kind() {
    static const CompensationKeys keys = keys_of("kulla_conty");
    static const ModelKind k{
        "kulla_conty",
        "Model L1 + Kulla & Conty's energy-compensation lobe, every order [Kulla & Conty 2017]",
        {keys.albedo, keys.rays},
        [](TableReader& r, const ModelContext& c) {
            return read_compensation(r, c, Compensation::kulla_conty, "kulla_conty", keys,
                                     "Kulla & Conty's compensation lobe [Kulla & Conty 2017]");
        }};
    return k;
}

const ModelKind& turquin_model_kind() {
    static const CompensationKeys keys = keys_of("turquin");
    static const ModelKind k{"turquin",
                             "Model L1 scaled by 1 + F0 (1 - E) / E, every order [Turquin 2019]",
                             {keys.albedo, keys.rays},
                             [](TableReader& r, const ModelContext& c) {
                                 return read_compensation(
                                     r, c, Compensation::turquin, "turquin", keys,
                                     "Turquin's scaling 1 + F0 (1 - E) / E [Turquin 2019]");
                             }};
    return k;
}

} // namespace gonio
