#include "gonio/model/pbrdf_model.h"

#include "gonio/model/model_kind.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tbb/parallel_for.h>

namespace gonio {

namespace {
double normal_cdf(double x) {
    return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

// E[(1 - t s)_+] for s ~ N(mu, sigma^2), t >= 0: the lobe's visible projected area per unit
// cos(theta) (closed form of C19 Eq. 12-13's integral for one non-centred Beckmann lobe).
double visible_fraction(double t, double mu, double sigma) {
    const double a = 1 - t * mu;
    if (t * sigma <= 0) return std::max(a, 0.0);
    const double z = a / (t * sigma);
    return a * normal_cdf(z) + t * sigma * std::exp(-0.5 * z * z) / std::sqrt(2 * kPi);
}

const double kThetaTop = kPi / 2 - 1e-6;
} // namespace

std::vector<SlopeLobe> fit_slope_lobes(const HeightField& s, double sigma_eps) {
    // k_i: standard deviation such that its half maximum lies at half the seed spacing (one texel)
    // [C19 section 3.1]; the weight of texel offset d along one axis is its integral over the
    // texel.
    const double sd = 0.5 / std::sqrt(2 * std::log(2.0));
    double w1[5], total = 0;
    for (int d = -2; d <= 2; ++d)
        total += w1[d + 2] = normal_cdf((d + 0.5) / sd) - normal_cdf((d - 0.5) / sd);
    for (double& w : w1) w /= total;
    std::vector<SlopeLobe> lobes(size_t(s.n) * s.n);
    tbb::parallel_for(0, s.n, [&](int y) {
        for (int x = 0; x < s.n; ++x) {
            double ep = 0, eq = 0, epp = 0, eqq = 0, epq = 0; // C19 Eq. 5-6
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx) {
                    const double w = w1[dx + 2] * w1[dy + 2];
                    const double p = s.p(x + dx, y + dy), q = s.q(x + dx, y + dy);
                    ep += w * p, eq += w * q, epp += w * p * p, eqq += w * q * q, epq += w * p * q;
                }
            SlopeLobe& l = lobes[size_t(y) * s.n + x];
            l.mx = ep, l.my = eq;
            const double sx = std::max(std::sqrt(std::max(0.0, epp - ep * ep)), sigma_eps);
            const double sy = std::max(std::sqrt(std::max(0.0, eqq - eq * eq)), sigma_eps);
            l.sxx = sx * sx, l.syy = sy * sy;
            l.sxy = std::clamp(epq - ep * eq, -0.999 * sx * sy, 0.999 * sx * sy);
        }
    });
    return lobes;
}

PBrdfModel::PBrdfModel(std::vector<SlopeLobe> lobes, FresnelTerm fresnel, int theta_nodes,
                       int phi_nodes)
    : fresnel_(std::move(fresnel)), theta_nodes_(theta_nodes), phi_nodes_(phi_nodes) {
    if (lobes.empty()) throw std::invalid_argument("the P-BRDF needs at least one lobe");
    double sx2 = 0, sy2 = 0; // the mixture's second moments of slope
    for (const SlopeLobe& s : lobes) {
        const double det = s.sxx * s.syy - s.sxy * s.sxy;
        if (!(det > 0)) throw std::invalid_argument("a lobe's covariance is not positive definite");
        lobes_.push_back(
            {s, s.syy / det, -s.sxy / det, s.sxx / det, 1 / (2 * kPi * std::sqrt(det))});
        mean_x_ += s.mx / double(lobes.size()), mean_y_ += s.my / double(lobes.size());
        sx2 += (s.sxx + s.mx * s.mx) / double(lobes.size());
        sy2 += (s.syy + s.my * s.my) / double(lobes.size());
    }
    // The cell integrator's scales, as a Beckmann lobe's (alpha = sqrt(2) sigma) from the whole
    // mixture: the sum of a texel's lobes is far smoother than any one of them (sigma_eps), and
    // resolving each would cost 10x more evaluations for the same cell averages.
    narrow_ = std::sqrt(2 * std::min(sx2, sy2));
    wide_ = std::sqrt(2 * std::max(sx2, sy2));
    table_.assign(size_t(theta_nodes_) * phi_nodes_, 0.0);
    tbb::parallel_for(0, theta_nodes_ * phi_nodes_, [&](int k) {
        const double t = std::min(kThetaTop, kPi / 2 * (k / phi_nodes_) / (theta_nodes_ - 1));
        const Vec3 v = spherical_direction(t, kTwoPi * (k % phi_nodes_) / phi_nodes_);
        table_[size_t(k)] = visible_area(v) / v.z;
    });
}

double PBrdfModel::D(const Vec3& m) const {
    if (m.z <= 0) return 0.0;
    const double px = -m.x / m.z, py = -m.y / m.z; // C19 slope of m
    double sum = 0;
    for (const Lobe& l : lobes_) {
        const double dx = px - l.s.mx, dy = py - l.s.my;
        const double q = l.ia * dx * dx + 2 * l.ib * dx * dy + l.ic * dy * dy;
        if (q < 80) sum += l.norm * std::exp(-0.5 * q); // C19 Eq. 4
    }
    const double c2 = m.z * m.z;
    return sum / double(lobes_.size()) / (c2 * c2); // C19 Eq. 2 and 9, W_i = 1 / a
}

double PBrdfModel::projected_area(const Vec3& v) const {
    // C19 Eq. 17: each lobe's mean normal n_i ~ (-mu_x, -mu_y, 1): <v, n_i> / (n_i . n) =
    // max(0, v.z - v.x mu_x - v.y mu_y).
    double sum = 0;
    for (const Lobe& l : lobes_) sum += std::max(0.0, v.z - v.x * l.s.mx - v.y * l.s.my);
    return sum / double(lobes_.size());
}

double PBrdfModel::visible_area(const Vec3& v) const {
    if (v.z <= 0) return 0.0;
    const double sin_t = std::sqrt(std::max(0.0, 1 - v.z * v.z));
    const double t = sin_t / v.z;
    const double cx = sin_t > 0 ? v.x / sin_t : 1.0, cy = sin_t > 0 ? v.y / sin_t : 0.0;
    double sum = 0;
    for (const Lobe& l : lobes_) {
        const double mu = cx * l.s.mx + cy * l.s.my;
        const double var = cx * cx * l.s.sxx + 2 * cx * cy * l.s.sxy + cy * cy * l.s.syy;
        sum += visible_fraction(t, mu, std::sqrt(var));
    }
    return v.z * sum / double(lobes_.size());
}

double PBrdfModel::lambda(const Vec3& v) const {
    return visible_area(v) / projected_area(v) - 1; // C19 Eq. 14-15
}

double PBrdfModel::visible_area_table(const Vec3& v) const {
    const double theta = std::acos(std::clamp(v.z, 0.0, 1.0));
    const double x = std::min(theta / (kPi / 2), 1.0) * (theta_nodes_ - 1);
    const int j = std::min(int(x), theta_nodes_ - 2);
    const double fx = x - j;
    double phi = std::atan2(v.y, v.x);
    if (phi < 0) phi += kTwoPi;
    const double y = phi / kTwoPi * phi_nodes_;
    const int l = std::min(int(y), phi_nodes_ - 1), l1 = (l + 1) % phi_nodes_;
    const double fy = y - l;
    auto at = [&](int r, int c) { return table_[size_t(r) * phi_nodes_ + c]; };
    return v.z * ((1 - fx) * ((1 - fy) * at(j, l) + fy * at(j, l1)) +
                  fx * ((1 - fy) * at(j + 1, l) + fy * at(j + 1, l1)));
}

void PBrdfModel::eval_cosine(const Vec3& i, const Vec3& o, double* out) const {
    const int nc = channels();
    Vec3 h;
    if (!reflection_half_vector(i, o, h)) {
        for (int c = 0; c < nc; ++c) out[c] = 0.0;
        return;
    }
    // C19 Eq. 7 with G1(v) = A_P(v) / visible(v) [Eq. 11, 16]: the projected areas cancel.
    const double geometric = D(h) * o.z / (4 * visible_area_table(i) * visible_area_table(o));
    fresnel_.eval(dot(i, h), out);
    for (int c = 0; c < nc; ++c) out[c] *= geometric;
}

} // namespace gonio

namespace gonio {
namespace {
const Key kSigmaEps = Key::number("pbrdf_sigma_eps", {1e-4, 1},
                                  "pbrdf: the floor σ_ε on each lobe's slope deviations")
                          .fallback(0.01)
                          .cited("C19 section 3.2");
}
// Fitted to the traced surface's slopes, so it needs the surface; specular facets only.
const ModelKind& pbrdf_model_kind() {
    static const ModelKind k{
        "pbrdf",
        "Chermain et al.'s P-BRDF fitted to the surface's slopes [C19 Eq. 7]",
        {kSigmaEps},
        [](TableReader& r, const ModelContext& c) {
            if (c.facets.diffuse)
                r.fail("models", "\"pbrdf\" is a specular model; for " + c.facets.type +
                                     " facets use \"il\" (and \"vcavity\")");
            ModelChoice m;
            m.name = "pbrdf";
            m.compared_with = "l1";
            m.needs_surface = true;
            m.description = "Chermain et al.'s P-BRDF [C19 Eq. 7, 9, 13-17]: one non-centred "
                            "Beckmann lobe per texel of the surface, the whole patch as footprint";
            m.build = [sigma_eps = r.number(kSigmaEps), fresnel = c.facets.fresnel](
                          const HeightField* surface) -> std::unique_ptr<BrdfModel> {
                return std::make_unique<PBrdfModel>(fit_slope_lobes(*surface, sigma_eps), fresnel);
            };
            return m;
        }};
    return k;
}
} // namespace gonio
