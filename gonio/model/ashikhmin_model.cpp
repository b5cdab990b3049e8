#include "gonio/model/ashikhmin_model.h"

#include "core/hemisphere_integral.h"
#include "core/parallel.h"
#include "gonio/model/model_kind.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

namespace {
// The last table row sits just above the horizon, where the exact integrals are still defined.
constexpr double kThetaTop = kPi / 2 - 1e-7;

// A "cylindrical" Gaussian of slopes across x: exp(-tan^2 theta cos^2 phi / sigma^2) [A00 Eq. 34
// with sigma_y infinite].
double cylindrical_gaussian(const Vec3& h, double sigma) {
    if (h.z <= 0) return 0.0;
    const double sx = h.x / h.z;
    return std::exp(-sx * sx / (sigma * sigma));
}
} // namespace

NormalDensity density_of(const Ndf& ndf) {
    return {[&ndf](const Vec3& h) { return ndf.D(h); }, ndf.narrowest_feature(),
            ndf.widest_feature(), ndf.describe()};
}

NormalDensity satin_density() {
    // A00 section 6.3: each part normalised (the weights are their areas), p = 0.7 flats + 0.3
    // ends.
    const double flats = hemisphere_integral(
        [](const Vec3& h) { return cylindrical_gaussian(h, 0.1); }, 0.05, nullptr, 1e-10);
    const double ends = hemisphere_integral(
        [](const Vec3& h) { return cylindrical_gaussian(h, 0.3); }, 0.05, nullptr, 1e-10);
    return {[flats, ends](const Vec3& h) {
                return 0.7 * cylindrical_gaussian(h, 0.1) / flats +
                       0.3 * cylindrical_gaussian(h, 0.3) / ends;
            },
            0.1, 0.3,
            "satin(0.7 cylindrical Gaussian 0.1 + 0.3 cylindrical Gaussian 0.3) [A00 6.3]"};
}

NormalDensity velvet_density(double sigma) {
    return {[sigma](const Vec3& h) {
                if (h.z <= 0) return 0.0;
                const double s2 = std::max(1e-300, 1 - h.z * h.z);
                return std::exp(-h.z * h.z / s2 / (sigma * sigma)); // A00 Eq. 35
            },
            0.5 * sigma, kPi / 2, "velvet(sigma=" + std::to_string(sigma) + ") [A00 Eq. 35]"};
}

AshikhminModel::AshikhminModel(NormalDensity p, FresnelTerm fresnel, AshikhminSettings s)
    : p_(std::move(p)), fresnel_(std::move(fresnel)), s_(std::move(s)) {
    const int nc = channels();
    if (s_.rho_d.size() == 1) s_.rho_d.assign(size_t(nc), s_.rho_d[0]);
    if (int(s_.rho_d.size()) != nc)
        throw std::invalid_argument("rho_d needs one value or one per channel");
    if (s_.theta_nodes < 3 || s_.phi_nodes < 4)
        throw std::invalid_argument("the tables need at least 3 theta and 4 phi nodes");
    mean_cos_ = hemisphere_integral([&](const Vec3& h) { return h.z * p_.p(h); }, p_.narrowest,
                                    nullptr, 1e-10);
    // Isotropic p: the tables depend on theta only.
    bool iso = true;
    for (double t : {0.1, 0.4, 0.9, 1.3})
        for (int l = 1; l < 16 && iso; ++l) {
            const double a = p_.p(spherical_direction(t, 0.0));
            const double b = p_.p(spherical_direction(t, kTwoPi * l / 16.0));
            iso = std::abs(a - b) <= 1e-12 * std::max(std::abs(a), 1e-300);
        }
    theta_nodes_ = s_.theta_nodes, phi_nodes_ = iso ? 1 : s_.phi_nodes;
    const int nodes = theta_nodes_ * phi_nodes_;
    auto node_direction = [&](int n) {
        const double t = std::min(kThetaTop, kPi / 2 * (n / phi_nodes_) / (theta_nodes_ - 1));
        return spherical_direction(t, kTwoPi * (n % phi_nodes_) / phi_nodes_);
    };
    g_.assign(size_t(nodes), 0.0);
    parallel_for(0, nodes, [&](int n) { g_[size_t(n)] = g_exact(node_direction(n)); });
    diffuse_scale_.assign(size_t(nc), 0.0), diffuse_level_.assign(size_t(nc), 1.0);
    diffuse_albedo_ = s_.rho_d;
    if (s_.diffuse == AshikhminDiffuse::none) return; // R is tabulated for the diffuse term only
    r_.assign(size_t(nodes) * nc, 0.0);
    parallel_for(0, nodes * nc,
                 [&](int k) { r_[size_t(k)] = reflectance_exact(node_direction(k / nc), k % nc); });
    // The diffuse term's scale c: with rho_d = 1 the surface returns all it receives (dielectric),
    // or f0 of it (metal): c = 1 / int (level - R(k))_+ (k.n) dw_k  [A00 Eq. 28-30].
    std::vector<double> f0(static_cast<size_t>(nc));
    fresnel_.eval(1.0, f0.data());
    for (int c = 0; c < nc; ++c) {
        if (s_.diffuse == AshikhminDiffuse::metal) diffuse_level_[c] = diffuse_albedo_[c] = f0[c];
        const double a = hemisphere_integral(
            [&](const Vec3& k) {
                return k.z * std::max(0.0, diffuse_level_[c] - reflectance(k, c));
            },
            0.1, nullptr, 1e-9);
        diffuse_scale_[c] = a > 0 ? 1.0 / a : 0.0;
    }
}

double AshikhminModel::g_exact(const Vec3& k) const {
    // A00 Eq. 18 over the hemisphere of h with h.k > 0 (k.n > 0: p lives on the upper hemisphere).
    return hemisphere_integral([&](const Vec3& h) { return std::max(0.0, dot(h, k)) * p_.p(h); },
                               p_.narrowest, &k, 1e-8);
}

double AshikhminModel::table(const std::vector<double>& t, const Vec3& k, int stride,
                             int offset) const {
    const double theta = std::acos(std::clamp(k.z, 0.0, 1.0));
    const double x = std::min(theta / (kPi / 2), 1.0) * (theta_nodes_ - 1);
    const int j = std::min(int(x), theta_nodes_ - 2);
    const double fx = x - j;
    auto at = [&](int row, int col) { return t[size_t(row * phi_nodes_ + col) * stride + offset]; };
    if (phi_nodes_ == 1) return (1 - fx) * at(j, 0) + fx * at(j + 1, 0);
    double phi = std::atan2(k.y, k.x);
    if (phi < 0) phi += kTwoPi;
    const double y = phi / kTwoPi * phi_nodes_;
    const int l = std::min(int(y), phi_nodes_ - 1), l1 = (l + 1) % phi_nodes_;
    const double fy = y - l;
    return (1 - fx) * ((1 - fy) * at(j, l) + fy * at(j, l1)) +
           fx * ((1 - fy) * at(j + 1, l) + fy * at(j + 1, l1));
}

double AshikhminModel::g(const Vec3& k) const {
    return table(g_, k, 1, 0);
}

double AshikhminModel::reflectance(const Vec3& k, int channel) const {
    return r_.empty() ? reflectance_exact(k, channel) : table(r_, k, channels(), channel);
}

void AshikhminModel::specular_cosine(const Vec3& i, const Vec3& o, double* out) const {
    const int nc = channels();
    Vec3 h;
    if (!reflection_half_vector(i, o, h)) {
        for (int c = 0; c < nc; ++c) out[c] = 0.0;
        return;
    }
    const double g1 = g(i), g2 = g(o);
    // A00 Eq. 11 with P(k) = (k.n) <h.n> / g(k) [Eq. 25]: the uncorrelated product gives
    // <h.n> / (4 g1 g2) [Eq. 26], the correlated min 1 / (4 max(g1 o.n, g2 i.n)) [Eq. 14].
    double t = 0;
    if (s_.correlation_width > 0) {
        const double cross = i.x * o.y - i.y * o.x, along = i.x * o.x + i.y * o.y;
        const double phi = (cross == 0 && along == 0) ? 0.0 : std::atan2(cross, along);
        t = std::exp(-0.5 * phi * phi / (s_.correlation_width * s_.correlation_width));
    }
    const double shadow =
        (1 - t) * mean_cos_ / (g1 * g2) + (t > 0 ? t / std::max(g1 * o.z, g2 * i.z) : 0.0);
    const double geometric = p_.p(h) * shadow * o.z / 4;
    fresnel_.eval(dot(i, h), out);
    for (int c = 0; c < nc; ++c) out[c] *= geometric;
}

double AshikhminModel::reflectance_exact(const Vec3& k, int channel) const {
    // A00 Eq. 29 over half vectors: dw_k' = 4 (k.h) dw_h, k' the mirror image of k about h.
    std::vector<double> f(static_cast<size_t>(channels()));
    return hemisphere_integral(
        [&](const Vec3& h) {
            const double kh = dot(k, h);
            const Vec3 o = 2 * kh * h - k;
            if (kh <= 0 || o.z <= 0) return 0.0;
            specular_cosine(k, o, f.data());
            return f[size_t(channel)] * 4 * kh;
        },
        p_.narrowest, &k, 1e-4);
}

void AshikhminModel::eval_cosine(const Vec3& i, const Vec3& o, double* out) const {
    specular_cosine(i, o, out);
    if (s_.diffuse == AshikhminDiffuse::none || i.z <= 0 || o.z <= 0) return;
    for (int c = 0; c < channels(); ++c) {
        // A00 Eq. 30 (dielectric) or its metal variant (section 5.1), clamped at 0.
        const double a = std::max(0.0, diffuse_level_[c] - reflectance(i, c));
        const double b = std::max(0.0, diffuse_level_[c] - reflectance(o, c));
        out[c] += diffuse_scale_[c] * a * b * diffuse_albedo_[c] * o.z;
    }
}

} // namespace gonio

namespace gonio {
// The normals' density of the generated BRDF.
enum class AshikhminDensity { ndf, satin, velvet };
template <>
struct EnumNames<AshikhminDensity> {
    static constexpr const char* what = "distribution";
    static constexpr const char* names[] = {"ndf", "satin", "velvet"};
};
namespace {
const Key kTable = Key::table("ashikhmin", "ashikhmin: its settings (the `model.ashikhmin` keys)")
                       .note_default("{}");
const Key kDistribution = Key::string("distribution", enum_names<AshikhminDensity>(),
                                      "the normals' density: the case's NDF, satin [A00 section "
                                      "6.3] or velvet [A00 Eq. 35]")
                              .fallback("ndf");
const Key kSigma =
    Key::number("sigma", {0.01, 10}, "velvet's width").fallback(0.5).cited("A00 Eq. 35");
const Key kCorrelation = Key::number("correlation_width", {0, 90},
                                     "0: uncorrelated shadowing [A00 Eq. 13]; A00 uses 15 with "
                                     "Eq. 14")
                             .in_unit("degrees")
                             .fallback(0.0);
const Key kDiffuse = Key::string("diffuse", enum_names<AshikhminDiffuse>(),
                                 "the diffuse term [A00 Eq. 28-30] or its metal variant [A00 "
                                 "section 5.1]")
                         .fallback("none");
const Key kRhoD = Key::numbers("rho_d", {0, 1}, "dielectric diffuse albedo (one or per channel)")
                      .fallback(std::vector<double>{1.0});
const Key kThetaNodes =
    Key::integer("theta_nodes", {3, 1000}, "rows of the g and R tables").fallback(61.0);
const Key kPhiNodes =
    Key::integer("phi_nodes", {4, 1000}, "columns of the g and R tables (anisotropic p)")
        .fallback(32.0);
const std::vector<Key> kSubKeys = {kDistribution, kSigma,      kCorrelation, kDiffuse,
                                   kRhoD,         kThetaNodes, kPhiNodes};
} // namespace

std::vector<KeyGroup> ashikhmin_key_groups() {
    return {{"model.ashikhmin", "", "the table `model.ashikhmin`", kSubKeys}};
}

// Held against L1 without a diffuse term, against every order with one; specular facets only.
const ModelKind& ashikhmin_model_kind() {
    static const ModelKind k{
        "ashikhmin",
        "Ashikhmin-Premoze-Shirley generated BRDF [A00 Eq. 11, 14, 25-30]",
        {kTable},
        [](TableReader& r, const ModelContext& c) {
            if (c.facets.diffuse)
                r.fail("models", "\"ashikhmin\" is a specular model; for " + c.facets.type +
                                     " facets use \"il\" (and \"vcavity\")");
            AshikhminSettings s;
            using Density = AshikhminDensity;
            Density which = Density::ndf;
            double sigma = 0.5;
            if (r.has(kTable.name)) {
                TableReader a = r.table(kTable);
                a.allow_only({&kSubKeys});
                which = enum_named<Density>(a.string(kDistribution));
                sigma = a.number(kSigma);
                s.correlation_width = radians(a.number(kCorrelation));
                s.diffuse = enum_named<AshikhminDiffuse>(a.string(kDiffuse));
                s.rho_d = a.number_list(kRhoD);
                if (s.rho_d.size() != 1 && int(s.rho_d.size()) != c.facets.channels)
                    a.fail("rho_d", "has " + std::to_string(s.rho_d.size()) +
                                        " values; give one, or one per channel (" +
                                        std::to_string(c.facets.channels) + ")");
                s.theta_nodes = static_cast<int>(a.integer(kThetaNodes));
                s.phi_nodes = static_cast<int>(a.integer(kPhiNodes));
            }
            auto density = [which, sigma](const Ndf& ndf) {
                return which == Density::satin    ? satin_density()
                       : which == Density::velvet ? velvet_density(sigma)
                                                  : density_of(ndf);
            };
            ModelChoice m;
            m.name = "ashikhmin";
            m.compared_with =
                s.diffuse != AshikhminDiffuse::none ? ModelTarget::linf : ModelTarget::l1;
            m.description = "Ashikhmin-Premoze-Shirley generated BRDF [A00 Eq. 11, 14, 25-30] of " +
                            density(*c.ndf).description;
            m.build =
                integrated(c,
                           [ndf = c.ndf, density, fresnel = c.facets.fresnel,
                            s](const HeightField*) -> std::unique_ptr<BrdfModel> {
                               return std::make_unique<AshikhminModel>(density(*ndf), fresnel, s);
                           });
            return m;
        }};
    return k;
}
} // namespace gonio
