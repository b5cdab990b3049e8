#include "gonio/fit/fit_problem.h"

#include "core/check.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/energy_compensation.h"
#include "gonio/model/microfacet_model.h"
#include "gonio/model/smith_random_walk.h"
#include "gonio/trace/gonioreflectometer.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {
std::string number(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}
// The cells' quadrature while fitting: the result file's models use 1e-6; a fit that moves its
// parameters by more than 1e-4 of themselves needs no more than 1e-5, a search from several
// starts no more than 1e-3.
CellQuadrature fit_quadrature(bool coarse) {
    CellQuadrature q;
    q.rel_tol = coarse ? 1e-3 : 1e-5;
    return q;
}
} // namespace

FitProblem::FitProblem(const ResultCase& c, const FitOptions& o) : c_(c), o_(o), sensor_(c.cells) {
    auto fail = [&](const std::string& why) {
        throw std::runtime_error(c.file + ", case " + c.name + ": " + why);
    };
    const FacetSpec& facets = c.config.material;
    if (facets.diffuse)
        fail("fit fits the specular microfacet model (Model L1); " + facets.type +
             " facets have none");
    if (o.with != FitWith::none && o.orders == FitOrders::l1)
        fail("--with " + std::string(name_of(o.with)) +
             " adds orders 2 and up: fit it to every order (--orders linf)");
    if ((o.with == FitWith::kulla_conty || o.with == FitWith::turquin) && facets.transmits)
        fail("--with " + std::string(name_of(o.with)) +
             " compensates opaque facets; this case's are a dielectric (use --with heitz16)");

    // The family: its roughness, then every other numeric key in its range; keys of other kinds
    // keep their defaults.
    const NdfFamily* family = nullptr;
    std::string families;
    for (const NdfFamily* f : ndf_families()) {
        const bool alpha = std::any_of(f->keys.begin(), f->keys.end(),
                                       [](const Key& k) { return k.name == "alpha"; });
        if (!alpha) continue;
        families += (families.empty() ? "" : ", ") + f->name;
        if (f->name == o.family) family = f;
    }
    if (!family)
        throw std::runtime_error("--model " + o.family +
                                 ": not a family with a roughness; allowed: " + families);
    for (const Key& k : family->keys) {
        if (k.name == "alpha") {
            const double lo = std::max(k.range.lo, 1e-3), hi = std::min(k.range.hi, 3.0);
            if (o.anisotropic)
                params_.push_back({"alpha_x", lo, hi, 0.3}),
                    params_.push_back({"alpha_y", lo, hi, 0.3});
            else
                params_.push_back({"alpha", lo, hi, 0.3});
        } else if (k.name == "alpha_x" || k.name == "alpha_y") {
            continue;
        } else if (k.kind == KeyKind::number) {
            const double span = k.range.hi - k.range.lo;
            const double lo = k.range.lo + (k.range.lo_open ? 1e-6 * span : 0);
            const double hi = k.range.hi - (k.range.hi_open ? 1e-6 * span : 0);
            params_.push_back({k.name, lo, hi, k.number_default.value_or(0.5 * (lo + hi))});
            extra_keys_.push_back(k.name);
        } else if (k.number_default) {
            fixed_keys_.push_back(k.name + " = " + number(*k.number_default));
        } else if (k.string_default) {
            fixed_keys_.push_back(k.name + " = \"" + *k.string_default + "\"");
        } else if (!k.bool_default) {
            fail("--model " + o.family + ": its key " + k.name + " is not a number to fit");
        }
    }
    if (o.fresnel == FitFresnel::fit) {
        first_f0_ = int(params_.size());
        for (int ch = 0; ch < c.channels; ++ch) {
            std::string name = "f0";
            if (c.channels > 1)
                name += c.wavelength_nm.empty() ? "_" + std::to_string(ch)
                                                : "_" + number(c.wavelength_nm[size_t(ch)]);
            params_.push_back({name, 0.0, 1.0, 0.5});
        }
    }

    // The data: simulated cell averages (L1 or every order) with their standard errors, or a
    // model of a `gonio model` file.
    std::string error_set;
    if (c.simulated) {
        dataset_ = o.orders == FitOrders::l1 ? "brdf_l1" : "brdf_linf";
        error_set = dataset_ + "_stderr";
        if (!o.reference.empty())
            fail("--reference is for `gonio model` files; this case is traced");
    } else {
        std::string name = o.reference;
        if (name.empty())
            for (const char* m : {"l1", "heitz16", "vcavity"})
                if (c.has(std::string("model_") + m)) {
                    name = m;
                    break;
                }
        if (name.empty() || !c.has("model_" + name))
            fail("no simulation and no model to fit to (--reference NAME picks model_NAME)");
        dataset_ = "model_" + name;
        if (c.has(dataset_ + "_stderr")) error_set = dataset_ + "_stderr";
    }
    has_errors_ = !error_set.empty();
    const std::vector<double> d = c.read_map(dataset_);
    const std::vector<double> e = has_errors_ ? c.read_map(error_set) : std::vector<double>();

    const size_t np = c.phi_i_deg.size(), nc = size_t(c.channels), cells = size_t(c.cells);
    map_size_ = c.theta_i_deg.size() * np * cells * nc;
    const double max_theta = radians(o.max_theta_deg);
    const double rays = double(std::max(1LL, c.config.trace.rays));
    double peak = 0;
    for (double v : d) peak = std::max(peak, v);
    for (size_t t = 0; t < c.theta_i_deg.size(); ++t)
        for (size_t p = 0; p < np; ++p) {
            const double ti = radians(c.theta_i_deg[t]);
            if (ti > max_theta) continue;
            incidences_.push_back(t * np + p);
            for (size_t cell = 0; cell < cells; ++cell) {
                const SensorCell& s = sensor_.cell(int(cell));
                if (s.theta_center > max_theta) continue;
                for (size_t ch = 0; ch < nc; ++ch) {
                    const size_t i = ((t * np + p) * cells + cell) * nc + ch;
                    index_.push_back(i);
                    data_.push_back(d[i]);
                    // A traced cell's error, at least that of one ray (an empty cell's batch
                    // error is 0); a model's, a relative 1e-3 (the fit is then a relative one).
                    sigma_.push_back(has_errors_ && c.simulated
                                         ? std::max(e[i], 1 / (rays * s.projected_solid_angle))
                                     : has_errors_ ? std::max(e[i], 1e-3 * d[i] + 1e-9 * peak)
                                                   : 1e-3 * d[i] + 1e-9 * peak);
                    const double st = std::sin(s.theta_center), ct = std::cos(s.theta_center);
                    double w = 1;
                    switch (o.loss) {
                    case FitLoss::chi2:
                        w = 1;
                        break;
                    case FitLoss::ngan:
                        w = std::sin(ti);
                        break;
                    case FitLoss::low_l2:
                    case FitLoss::low_log:
                        w = std::sin(ti) / std::max(st, 1e-3);
                        break;
                    case FitLoss::bieron_l2:
                    case FitLoss::bieron_log:
                        w = std::sin(ti) * ct;
                        break;
                    }
                    weight_.push_back(std::sqrt(w));
                    cos_i_.push_back(std::cos(ti));
                }
            }
        }
    if (incidences_.empty() || index_.empty())
        fail("no incidence and cell within --max-theta " + number(o.max_theta_deg) + " degrees");
    if (std::all_of(weight_.begin(), weight_.end(), [](double w) { return w == 0; }))
        fail("the loss " + std::string(name_of(o.loss)) +
             " weights an incidence by sin(theta_i): it has nothing to fit at normal incidence");
    if (index_.size() <= params_.size()) fail("fewer data than parameters");
}

std::vector<double> FitProblem::clamped(const double* p) const {
    std::vector<double> v(params_.size());
    for (size_t k = 0; k < v.size(); ++k)
        v[k] = std::clamp(p[k], params_[k].lower, params_[k].upper);
    return v;
}

std::string FitProblem::ndf_toml(const double* p) const {
    const std::vector<double> v = clamped(p);
    std::string t = "type = \"" + o_.family + "\"\n";
    for (size_t k = 0; k < v.size(); ++k)
        if (int(k) < first_f0_ || first_f0_ < 0) t += params_[k].name + " = " + number(v[k]) + "\n";
    for (const std::string& line : fixed_keys_) t += line + "\n";
    return t;
}

std::vector<double> FitProblem::predict(const double* p, bool coarse) const {
    const std::vector<double> v = clamped(p);
    const std::shared_ptr<const Ndf> ndf = ndf_from_toml(ndf_toml(v.data()));
    const size_t nc = size_t(c_.channels), cells = size_t(c_.cells), np = c_.phi_i_deg.size();
    FresnelTerm fresnel = c_.config.material.fresnel;
    if (first_f0_ >= 0)
        fresnel = FresnelTerm::schlick(std::vector<double>(v.begin() + first_f0_, v.end()));
    const MaskingForm masking = c_.config.model.masking;
    const CellQuadrature q = fit_quadrature(coarse);
    std::shared_ptr<const AlbedoTable> table;
    if (o_.with == FitWith::kulla_conty || o_.with == FitWith::turquin)
        table = std::make_shared<const AlbedoTable>(AlbedoTable::smith(*ndf, masking, q));
    const std::vector<double> psa = sensor_.projected_solid_angles();
    std::vector<double> maps(incidences_.size() * cells * nc);
    for (size_t k = 0; k < incidences_.size(); ++k) {
        const size_t t = incidences_[k] / np, ph = incidences_[k] % np;
        const Vec3 wi = spherical_direction(radians(c_.theta_i_deg[t]), radians(c_.phi_i_deg[ph]));
        std::vector<double> energy;
        switch (o_.with) {
        case FitWith::none:
            energy = model_cell_energy(MicrofacetModel(*ndf, fresnel, masking), wi, sensor_, q);
            break;
        case FitWith::kulla_conty:
        case FitWith::turquin:
            energy = compensated_model(o_.with == FitWith::kulla_conty ? Compensation::kulla_conty
                                                                       : Compensation::turquin,
                                       ndf, fresnel, masking, q, table)
                         ->evaluate(wi, sensor_, 0, 0)
                         .energy;
            break;
        case FitWith::heitz16: {
            // Common random numbers: the same seed and streams for every parameter vector.
            TraceSettings st;
            st.rays = o_.walk_paths;
            st.orders = 2;
            st.seed = o_.seed;
            st.stream = k;
            std::vector<TraceResult> parts;
            if (first_f0_ >= 0) {
                parts.push_back(
                    smith_random_walk(*ndf, SpecularReflector(fresnel), sensor_, wi, st));
            } else {
                std::vector<std::unique_ptr<Material>> materials = c_.config.material.parts();
                for (size_t m = 0; m < materials.size(); ++m) {
                    TraceSettings part = st;
                    part.stream ^= std::uint64_t(m + 1) << 56;
                    parts.push_back(smith_random_walk(*ndf, *materials[m], sensor_, wi, part));
                }
            }
            const TraceResult r = concatenate_channels(parts);
            energy.assign(cells * nc, 0.0);
            for (int order = 0; order < r.orders; ++order)
                for (size_t i = 0; i < cells * nc; ++i)
                    energy[i] += r.energy[order * cells * nc + i];
            break;
        }
        }
        const std::vector<double> brdf = cell_brdf(std::move(energy), psa, nc);
        std::copy(brdf.begin(), brdf.end(), maps.begin() + long(k * cells * nc));
    }
    // Gather per residual: its incidence's slot, cell and channel.
    std::vector<double> m(index_.size());
    size_t slot = 0;
    for (size_t r = 0; r < index_.size(); ++r) {
        const size_t inc = index_[r] / (cells * nc), rest = index_[r] % (cells * nc);
        while (incidences_[slot] != inc) ++slot;
        m[r] = maps[slot * cells * nc + rest];
    }
    return m;
}

void FitProblem::residuals(const std::vector<double>& m, const std::vector<double>& d,
                           double* out) const {
    for (size_t k = 0; k < m.size(); ++k) {
        switch (o_.loss) {
        case FitLoss::chi2:
            out[k] = (d[k] - m[k]) / sigma_[k];
            break;
        case FitLoss::ngan:
        case FitLoss::low_l2:
        case FitLoss::bieron_l2:
            out[k] = weight_[k] * (m[k] - d[k]) * cos_i_[k];
            break;
        case FitLoss::low_log:
        case FitLoss::bieron_log:
            out[k] = weight_[k] *
                     (std::log1p(m[k] * cos_i_[k]) - std::log1p(std::max(0.0, d[k]) * cos_i_[k]));
            break;
        }
    }
}

std::vector<double> FitProblem::normalised(const std::vector<double>& m) const {
    std::vector<double> z(m.size());
    for (size_t k = 0; k < m.size(); ++k) z[k] = (data_[k] - m[k]) / sigma_[k];
    return z;
}

} // namespace gonio
