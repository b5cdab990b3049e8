#include "gonio/model/cell_integrator.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/quadrature.h"

namespace gonio {

namespace {

struct Rect {
    double z0, z1, p0, p1; // cos(theta) in [z0, z1], phi in [p0, p1]
};

class CellIntegrator {
  public:
    CellIntegrator(const MicrofacetModel& model, const Vec3& wi, const CellQuadrature& q)
        : model_(model), wi_(wi), q_(q), rule_(gauss_legendre(q.points)),
          nc_(model.channels()), mirror_{-wi.x, -wi.y, wi.z},
          narrow_(model.ndf().narrowest_feature()), wide_(model.ndf().widest_feature()) {}

    void integrate(const Rect& r, double* out) const {
        std::vector<double> coarse(nc_, 0.0);
        gauss(r, coarse.data());
        double scale = 0;
        for (double v : coarse) scale = std::max(scale, std::abs(v));
        refine(r, coarse.data(), std::max(q_.rel_tol * scale, 1e-15), 0, out);
    }

  private:
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

    // True while the rectangle could hide a lobe feature: wider than the narrowest feature and
    // within reach of the specular direction (lobes of the centred NDFs sit around it).
    bool must_split(const Rect& r) const {
        const double t0 = std::acos(std::min(1.0, r.z1)), t1 = std::acos(std::max(0.0, r.z0));
        const double dt = t1 - t0, dp = (r.p1 - r.p0) * std::sin(t1);
        const double size = std::sqrt(dt * dt + dp * dp);
        if (size <= 0.5 * narrow_) return false;
        const double zc = 0.5 * (r.z0 + r.z1), pc = 0.5 * (r.p0 + r.p1);
        const double sc = std::sqrt(std::max(0.0, 1.0 - zc * zc));
        const Vec3 centre{sc * std::cos(pc), sc * std::sin(pc), zc};
        // The reflected lobe is about twice as wide as the normal distribution's.
        return angle_between(centre, mirror_) < size + 12.0 * wide_;
    }

    void refine(const Rect& r, const double* coarse, double tol, int depth, double* out) const {
        const double zm = 0.5 * (r.z0 + r.z1), pm = 0.5 * (r.p0 + r.p1);
        const Rect kids[4] = {{r.z0, zm, r.p0, pm}, {zm, r.z1, r.p0, pm},
                              {r.z0, zm, pm, r.p1}, {zm, r.z1, pm, r.p1}};
        std::vector<double> part(4 * nc_, 0.0);
        for (int k = 0; k < 4; ++k) gauss(kids[k], &part[k * nc_]);
        double err = 0;
        for (int c = 0; c < nc_; ++c) {
            const double fine = part[c] + part[nc_ + c] + part[2 * nc_ + c] + part[3 * nc_ + c];
            err = std::max(err, std::abs(fine - coarse[c]));
        }
        if (depth >= q_.max_depth || (err <= tol && !must_split(r))) {
            for (int k = 0; k < 4; ++k)
                for (int c = 0; c < nc_; ++c) out[c] += part[k * nc_ + c];
            return;
        }
        for (int k = 0; k < 4; ++k) refine(kids[k], &part[k * nc_], 0.5 * tol, depth + 1, out);
    }

    const MicrofacetModel& model_;
    Vec3 wi_;
    CellQuadrature q_;
    const GaussLegendre& rule_;
    int nc_;
    Vec3 mirror_;
    double narrow_, wide_;
};

} // namespace

std::vector<double> model_cell_energy(const MicrofacetModel& model, const Vec3& wi,
                                      const BeckersSensor& sensor, const CellQuadrature& q) {
    const int nc = model.channels();
    std::vector<double> energy(static_cast<size_t>(sensor.cell_count()) * nc, 0.0);
    const CellIntegrator integrator(model, wi, q);
    // Cells are independent: the result does not depend on the thread count.
    tbb::parallel_for(0, sensor.cell_count(), [&](int c) {
        const SensorCell& cell = sensor.cell(c);
        const Rect r{std::cos(cell.theta_max), std::cos(cell.theta_min), cell.phi_min, cell.phi_max};
        integrator.integrate(r, &energy[static_cast<size_t>(c) * nc]);
    });
    return energy;
}

std::vector<double> albedo_from_cells(const std::vector<double>& energy, int channels) {
    std::vector<double> albedo(channels, 0.0);
    for (size_t i = 0; i < energy.size(); ++i) albedo[i % channels] += energy[i];
    return albedo;
}

} // namespace gonio
