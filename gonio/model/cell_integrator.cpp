#include "gonio/model/cell_integrator.h"

#include "core/parallel.h"
#include "core/quadrature.h"

#include <algorithm>
#include <cmath>

namespace gonio {

namespace {

struct Rect {
    double z0, z1, p0, p1; // cos(theta) in [z0, z1], phi in [p0, p1]
};

class CellIntegrator {
  public:
    CellIntegrator(const BrdfModel& model, const Vec3& wi, const CellQuadrature& q)
        : model_(model), wi_(wi), q_(q), rule_(gauss_legendre(q.points)), nc_(model.channels()) {
        const double narrow = model.narrowest_feature(), wide = model.widest_feature();
        theta_r_ = spherical_theta(wi);
        phi_r_ = spherical_phi({-wi.x, -wi.y, wi.z});
        // The reflected lobe around the mirror direction: tilting h by d in the plane of incidence
        // moves o by about 2d in theta, tilting it sideways moves o by only 2 d (i.h) across, and
        // i.h ~ cos(theta_i) + (polar offset of o)/2. At grazing incidence even a broad lobe has a
        // spike of width ~2 alpha cos(theta_i) at the mirror direction. Conservative (halved)
        // widths, and a reach of 6 slope widths:
        narrow_ = narrow;
        cos_i_ = wi.z;
        width_polar_ = narrow;
        reach_polar_ = 12.0 * wide;
        reach_across_ = 12.0 * wide * std::min(1.0, wi.z + 12.0 * wide);
    }

    // Adds the rectangle's integral into out; returns the error bound it reached relative to
    // its magnitude when the budget of pieces ran out first, else 0.
    double integrate(const Rect& r, double* out) const {
        std::vector<double> coarse(nc_, 0.0);
        gauss(r, coarse.data());
        Budget budget{q_.max_pieces};
        refine(r, coarse.data(), 0, budget, out);
        if (!budget.ran_out) return 0;
        double magnitude = 0;
        for (int c = 0; c < nc_; ++c) magnitude = std::max(magnitude, std::abs(out[c]));
        return magnitude > 0 ? budget.unresolved / magnitude : 1;
    }

  private:
    // Splits left to one cell, and the error estimates of the pieces accepted without meeting
    // the tolerance once they ran out.
    struct Budget {
        long pieces;
        bool ran_out = false;
        double unresolved = 0;
    };

    // Tensor Gauss-Legendre over the rectangle, added into out.
    void gauss(const Rect& r, double* out) const {
        const double hz = 0.5 * (r.z1 - r.z0), hp = 0.5 * (r.p1 - r.p0);
        const double cz = 0.5 * (r.z1 + r.z0), cp = 0.5 * (r.p1 + r.p0);
        std::vector<double> f(nc_);
        const int n = static_cast<int>(rule_.nodes.size());
        for (int a = 0; a < n; ++a) {
            const double z = cz + hz * rule_.nodes[a];
            const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
            for (int b = 0; b < n; ++b) {
                const double p = cp + hp * rule_.nodes[b];
                model_.eval_cosine(wi_, {s * std::cos(p), s * std::sin(p), z}, f.data());
                const double w = rule_.weights[a] * rule_.weights[b] * hz * hp;
                for (int c = 0; c < nc_; ++c) out[c] += w * f[c];
            }
        }
    }

    // Angular extents of a rectangle: polar, and azimuthal at its widest.
    static void extents(const Rect& r, double& polar, double& azimuthal) {
        const double t0 = std::acos(std::min(1.0, r.z1)), t1 = std::acos(std::max(0.0, r.z0));
        polar = t1 - t0;
        azimuthal = (r.p1 - r.p0) * std::sin(t1);
    }

    // True while the rectangle could hide a feature: wider than the lobe in theta or across and
    // within reach of the mirror direction (lobes of the centred NDFs sit around it), or wider
    // than the masking band of a grazing incidence. `split_polar` tells which side to halve: the
    // one largest relative to the feature's width.
    bool must_split(const Rect& r, bool& split_polar) const {
        double dt, dp;
        extents(r, dt, dp);
        const double t0 = std::acos(std::min(1.0, r.z1)), t1 = std::acos(std::max(0.0, r.z0));
        // Masking: G changes as Lambda(o) reaches Lambda(i), at theta_o ~ theta_i for every
        // azimuth: near grazing a band as thin as the incidence's distance to the horizon. The
        // lobe's own needs come first.
        const double band = kPi / 2 - theta_r_;
        const bool in_band = t1 > theta_r_ - 4 * band && dt > 0.5 * band;
        auto band_split = [&] {
            if (in_band) split_polar = true;
            return in_band;
        };
        if (std::isinf(narrow_)) return band_split(); // no lobe
        // Distances from the mirror direction to the rectangle's theta and phi intervals.
        const double off_polar = std::max({0.0, t0 - theta_r_, theta_r_ - t1});
        double off_phi = 0;
        if (!(phi_r_ >= r.p0 && phi_r_ <= r.p1)) {
            const double a = std::abs(phi_r_ - r.p0), b = std::abs(phi_r_ - r.p1);
            off_phi = std::min({a, kTwoPi - a, b, kTwoPi - b});
        }
        // Measured at the polar angle closest to the mirror direction (0 at the pole).
        const double across = off_phi * std::sin(std::clamp(theta_r_, t0, t1));
        if (off_polar > reach_polar_ || across > reach_across_) return band_split();
        // The grazing spike is narrow only near the mirror direction: `across` away from it, the
        // half vector's tilt changes on the scale of that distance itself (else a whole horizon
        // band would be cut to the spike's width).
        const double width_across =
            narrow_ * std::max(cos_i_ + 0.5 * off_polar, 1e-4) + 0.03 * across;
        const double rel_t = dt / width_polar_, rel_p = dp / width_across;
        if (rel_t <= 0.5 && rel_p <= 0.5) return band_split();
        split_polar = rel_t >= rel_p;
        return true;
    }

    // Halves the longer angular side (near the pole, thin azimuthal wedges need no further
    // azimuthal splits), or the side the lobe needs resolved. A rectangle is accepted when
    // splitting changes its integral by less than rel_tol of that integral, or by less than an
    // absolute floor proportional to its solid angle (rel_tol * 1e-4 of the hemisphere's share), so
    // negligible regions stop early. A cell whose integrand has kinks everywhere (a measured
    // NDF's table) can need more splits than exist: the budget of pieces bounds its work, and the
    // error left in the pieces it could not split is reported instead of the tolerance.
    void refine(const Rect& r, const double* coarse, int depth, Budget& budget, double* out) const {
        double dt, dp;
        extents(r, dt, dp);
        bool split_polar = dt >= dp;
        const bool forced = must_split(r, split_polar);
        Rect kids[2];
        if (split_polar) {
            const double zm = 0.5 * (r.z0 + r.z1);
            kids[0] = {r.z0, zm, r.p0, r.p1};
            kids[1] = {zm, r.z1, r.p0, r.p1};
        } else {
            const double pm = 0.5 * (r.p0 + r.p1);
            kids[0] = {r.z0, r.z1, r.p0, pm};
            kids[1] = {r.z0, r.z1, pm, r.p1};
        }
        std::vector<double> part(2 * nc_, 0.0);
        for (int k = 0; k < 2; ++k) gauss(kids[k], &part[k * nc_]);
        double err = 0, magnitude = 0;
        for (int c = 0; c < nc_; ++c) {
            const double fine = part[c] + part[nc_ + c];
            err = std::max(err, std::abs(fine - coarse[c]));
            magnitude = std::max(magnitude, std::abs(fine));
        }
        const double area = (r.z1 - r.z0) * (r.p1 - r.p0);
        const double tol = q_.rel_tol * (magnitude + 1e-4 * area / kTwoPi);
        const bool settled = err <= tol && !forced;
        if (depth >= q_.max_depth || settled || budget.pieces <= 0) {
            if (!settled && depth < q_.max_depth && err > tol)
                budget.ran_out = true, budget.unresolved += err;
            for (int k = 0; k < 2; ++k)
                for (int c = 0; c < nc_; ++c) out[c] += part[k * nc_ + c];
            return;
        }
        --budget.pieces;
        for (int k = 0; k < 2; ++k) refine(kids[k], &part[k * nc_], depth + 1, budget, out);
    }

    const BrdfModel& model_;
    Vec3 wi_;
    CellQuadrature q_;
    const GaussLegendre& rule_;
    int nc_;
    double theta_r_ = 0, phi_r_ = 0;
    double narrow_ = 0, cos_i_ = 1;
    double width_polar_ = 0, reach_polar_ = 0, reach_across_ = 0;
};

} // namespace

std::vector<double> model_cell_energy(const BrdfModel& model, const Vec3& wi,
                                      const BeckersSensor& sensor, const CellQuadrature& q,
                                      double* reached) {
    const int nc = model.channels();
    std::vector<double> short_by(sensor.cell_count(), 0.0);
    std::vector<double> energy(static_cast<size_t>(sensor.cell_count()) * nc, 0.0);
    for (const BrdfModel* term : model.terms()) {
        // A smooth term (no lobe: the IL body, whose every evaluation is a body_points^2 sum) is
        // as accurate with 2 points per axis and the same tolerance, in a quarter of the time
        // (bench/study.py, case D).
        CellQuadrature tq = q;
        if (std::isinf(term->narrowest_feature())) tq.points = std::min(q.points, 2);
        const CellIntegrator integrator(*term, wi, tq);
        // Cells are independent: the result does not depend on the thread count.
        parallel_for(0, sensor.cell_count(), [&](int c) {
            const SensorCell& cell = sensor.cell(c);
            const Rect r{std::cos(cell.theta_max), std::cos(cell.theta_min), cell.phi_min,
                         cell.phi_max};
            short_by[c] =
                std::max(short_by[c], integrator.integrate(r, &energy[static_cast<size_t>(c) * nc]));
        });
    }
    if (reached) *reached = std::max(q.rel_tol, *std::max_element(short_by.begin(), short_by.end()));
    return energy;
}

std::vector<double> albedo_from_cells(const std::vector<double>& energy, int channels) {
    std::vector<double> albedo(channels, 0.0);
    for (size_t i = 0; i < energy.size(); ++i) albedo[i % channels] += energy[i];
    return albedo;
}

} // namespace gonio
