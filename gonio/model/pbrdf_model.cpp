#include "gonio/model/pbrdf_model.h"

#include "core/parallel.h"
#include "gonio/model/model_kind.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

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
    parallel_for(0, s.n, [&](int y) {
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
    build_slope_grid();
    table_.assign(size_t(theta_nodes_) * phi_nodes_, 0.0);
    parallel_for(0, theta_nodes_ * phi_nodes_, [&](int k) {
        const double t = std::min(kThetaTop, kPi / 2 * (k / phi_nodes_) / (theta_nodes_ - 1));
        const Vec3 v = spherical_direction(t, kTwoPi * (k % phi_nodes_) / phi_nodes_);
        table_[size_t(k)] = visible_area(v) / v.z;
    });
}

void PBrdfModel::build_slope_grid() {
    // A lobe adds to D only where q = d^T Sigma^-1 d < 80, and the minimum of q over dy at a
    // given dx is dx^2 / sxx (over dx: dy^2 / syy): its reach is the box |dx| < sqrt(80 sxx),
    // |dy| < sqrt(80 syy), here widened by 5 % in q against q's round-off. Each grid cell lists,
    // in ascending order, the lobes whose box meets it or its neighbours (against the round-off
    // of the cell index): D sums the same terms in the same order as over every lobe, and so
    // returns the same bits.
    const size_t n = lobes_.size();
    std::vector<double> bx0(n), bx1(n), by0(n), by1(n);
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    double mean_wx = 0, mean_wy = 0;
    for (size_t i = 0; i < n; ++i) {
        const SlopeLobe& l = lobes_[i].s;
        const double wx = std::sqrt(84 * l.sxx), wy = std::sqrt(84 * l.syy);
        bx0[i] = l.mx - wx, bx1[i] = l.mx + wx, by0[i] = l.my - wy, by1[i] = l.my + wy;
        x0 = std::min(x0, bx0[i]), x1 = std::max(x1, bx1[i]);
        y0 = std::min(y0, by0[i]), y1 = std::max(y1, by1[i]);
        mean_wx += wx / double(n), mean_wy += wy / double(n);
    }
    if (!(x1 > x0 && y1 > y0 && std::isfinite(x1 - x0) && std::isfinite(y1 - y0))) {
        grid_all_ = true; // a lobe without a finite reach (not positive definite): no culling
        return;
    }
    grid_all_ = false;
    // Cells of about half a mean reach: each lobe in some 7 x 7 of them.
    grid_nx_ = std::clamp(int((x1 - x0) / (0.5 * mean_wx)), 1, 256);
    grid_ny_ = std::clamp(int((y1 - y0) / (0.5 * mean_wy)), 1, 256);
    grid_x0_ = x0, grid_y0_ = y0, grid_x1_ = x1, grid_y1_ = y1;
    grid_sx_ = grid_nx_ / (x1 - x0), grid_sy_ = grid_ny_ / (y1 - y0);
    auto cell_x = [&](double x) { return std::clamp(int((x - x0) * grid_sx_), 0, grid_nx_ - 1); };
    auto cell_y = [&](double y) { return std::clamp(int((y - y0) * grid_sy_), 0, grid_ny_ - 1); };
    std::vector<std::uint32_t> count(size_t(grid_nx_) * grid_ny_ + 1, 0);
    auto each_cell = [&](size_t i, auto&& f) {
        const int cx0 = std::max(cell_x(bx0[i]) - 1, 0),
                  cx1 = std::min(cell_x(bx1[i]) + 1, grid_nx_ - 1);
        const int cy0 = std::max(cell_y(by0[i]) - 1, 0),
                  cy1 = std::min(cell_y(by1[i]) + 1, grid_ny_ - 1);
        for (int cy = cy0; cy <= cy1; ++cy)
            for (int cx = cx0; cx <= cx1; ++cx) f(size_t(cy) * grid_nx_ + cx);
    };
    for (size_t i = 0; i < n; ++i) each_cell(i, [&](size_t c) { ++count[c + 1]; });
    for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    cell_start_ = count;
    cell_lobes_.resize(count.back());
    for (size_t i = 0; i < n; ++i) // ascending i: each cell's list is in the lobes' order
        each_cell(i, [&](size_t c) { cell_lobes_[count[c]++] = std::uint32_t(i); });
}

double PBrdfModel::D(const Vec3& m) const {
    if (m.z <= 0) return 0.0;
    const double px = -m.x / m.z, py = -m.y / m.z; // C19 slope of m
    double sum = 0;
    if (grid_all_) {
        for (const Lobe& l : lobes_) {
            const double dx = px - l.s.mx, dy = py - l.s.my;
            const double q = l.ia * dx * dx + 2 * l.ib * dx * dy + l.ic * dy * dy;
            if (q < 80) sum += l.norm * std::exp(-0.5 * q); // C19 Eq. 4
        }
    } else if (px >= grid_x0_ && px <= grid_x1_ && py >= grid_y0_ && py <= grid_y1_) {
        // (Outside the grid, or not finite, no lobe reaches: every q >= 80, the sum is 0.)
        const int cx = std::min(int((px - grid_x0_) * grid_sx_), grid_nx_ - 1);
        const int cy = std::min(int((py - grid_y0_) * grid_sy_), grid_ny_ - 1);
        const size_t c = size_t(cy) * grid_nx_ + cx;
        for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
            const Lobe& l = lobes_[cell_lobes_[k]];
            const double dx = px - l.s.mx, dy = py - l.s.my;
            const double q = l.ia * dx * dx + 2 * l.ib * dx * dy + l.ic * dy * dy;
            if (q < 80) sum += l.norm * std::exp(-0.5 * q); // C19 Eq. 4
        }
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
        // Far in front of the lobe, z = a / (t sigma) >= 9 (tested without the square root):
        // Phi(z) rounds to 1 and t sigma phi(z) = a phi(z) / z < 1.2e-19 a is below half an ulp
        // of a, so visible_fraction returns exactly a. Skipping its sqrt, erfc and exp there (most
        // of the table's directions: a normal map's lobes are narrow) is exact to the bit; so is
        // either branch down to z ~ 8.3, so the test's own rounding does not matter.
        const double a = 1 - t * mu;
        if (a > 0 && a * a >= 81 * (t * t) * var) {
            sum += a;
            continue;
        }
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
            m.compared_with = ModelTarget::l1;
            m.needs_surface = true;
            m.description = "Chermain et al.'s P-BRDF [C19 Eq. 7, 9, 13-17]: one non-centred "
                            "Beckmann lobe per texel of the surface, the whole patch as footprint";
            m.build = integrated(c,
                                 [sigma_eps = r.number(kSigmaEps), fresnel = c.facets.fresnel](
                                     const HeightField* surface) -> std::unique_ptr<BrdfModel> {
                                     return std::make_unique<PBrdfModel>(
                                         fit_slope_lobes(*surface, sigma_eps), fresnel);
                                 });
            return m;
        }};
    return k;
}
} // namespace gonio
