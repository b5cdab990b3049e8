#include "gonio/table/bsdf_table.h"

#include "gonio/table/result_case.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace gonio {

TableData table_data(const ResultCase& c, TableOrder order) {
    if (!c.simulated)
        throw std::runtime_error(c.file + ": case " + c.name +
                                 " holds models only (gonio model): no simulated orders");
    if (order == TableOrder::transmission && !c.transmits)
        throw std::runtime_error(c.file + ": case " + c.name + " (" + c.material +
                                 ") transmits nothing: it has no lower sensor");
    const char* f = "brdf_linf";
    const char* albedo = "linf_albedo";
    switch (order) {
    case TableOrder::l1:
        f = "brdf_l1", albedo = "l1_albedo";
        break;
    case TableOrder::l2plus:
        f = "brdf_l2plus", albedo = "l2plus_albedo";
        break;
    case TableOrder::linf:
        break;
    case TableOrder::transmission:
        f = "btdf_tinf", albedo = "transmitted_albedo";
        break;
    }
    TableData d;
    d.theta_i_deg = c.theta_i_deg;
    d.phi_i_deg = c.phi_i_deg;
    d.cells = c.cells;
    d.channels = c.channels;
    d.f = c.read_map(f);
    d.f_stderr = c.read_map(std::string(f) + "_stderr");
    d.albedo_stderr = c.read_albedo(std::string(albedo) + "_stderr");
    d.isotropic = c.isotropic;
    d.transmission = order == TableOrder::transmission;
    return d;
}

TableData model_table_data(const ResultCase& c, const std::string& model) {
    const std::string name = "model_" + model;
    if (!c.has(name))
        throw std::runtime_error(c.file + ": case " + c.name + " has no model " + model);
    TableData d;
    d.theta_i_deg = c.theta_i_deg;
    d.phi_i_deg = c.phi_i_deg;
    d.cells = c.cells;
    d.channels = c.channels;
    d.f = c.read_map(name);
    d.isotropic = c.isotropic;
    return d;
}

namespace {
constexpr int kMaxIsotropicSlices = 8; // azimuths an isotropic query averages
constexpr int kMaxBlend = 2 * kMaxIsotropicSlices;

std::string list_degrees(const std::vector<double>& v) {
    std::string s;
    for (double x : v) s += (s.empty() ? "" : ", ") + std::to_string(x).substr(0, 6);
    return "{" + s + "}";
}
} // namespace

BsdfTable::BsdfTable(TableData data) : data_(std::move(data)) {
    const size_t nt = data_.theta_i_deg.size(), np = data_.phi_i_deg.size();
    const size_t C = size_t(data_.channels), N = size_t(data_.cells);
    if (nt == 0 || np == 0 || N == 0 || C == 0)
        throw std::invalid_argument("BsdfTable: an empty sweep, sensor or channel list");
    if (data_.f.size() != nt * np * N * C)
        throw std::invalid_argument("BsdfTable: " + std::to_string(data_.f.size()) +
                                    " values for a sweep of " + std::to_string(nt) + " x " +
                                    std::to_string(np) + " incidences x " + std::to_string(N) +
                                    " cells x " + std::to_string(C) + " channels");
    sensor_ = std::make_unique<BeckersSensor>(data_.cells);
    grid_ = std::make_unique<SensorLobeGrid>(*sensor_);

    // Distinct sorted angles, and the stored index of each.
    std::vector<size_t> theta_order(nt), phi_order;
    for (size_t k = 0; k < nt; ++k) theta_order[k] = k;
    std::sort(theta_order.begin(), theta_order.end(),
              [&](size_t a, size_t b) { return data_.theta_i_deg[a] < data_.theta_i_deg[b]; });
    for (size_t k : theta_order) {
        if (!theta_.empty() && std::abs(data_.theta_i_deg[k] - theta_.back()) < 1e-9)
            throw std::invalid_argument(
                "BsdfTable: theta_i = " + std::to_string(data_.theta_i_deg[k]) +
                " appears twice in the sweep");
        theta_.push_back(data_.theta_i_deg[k]);
    }
    std::vector<std::pair<double, size_t>> phis;
    for (size_t k = 0; k < np; ++k) {
        double p = std::fmod(data_.phi_i_deg[k], 360.0);
        if (p < 0) p += 360;
        bool seen = false;
        for (const auto& q : phis) seen = seen || std::abs(q.first - p) < 1e-9;
        if (!seen) phis.emplace_back(p, k); // 360 repeats 0: the first one is kept
    }
    std::sort(phis.begin(), phis.end());
    for (const auto& [p, k] : phis) {
        phi_.push_back(p);
        phi_order.push_back(k);
    }
    if (!data_.isotropic) {
        double widest = 0;
        for (size_t k = 0; k < phi_.size(); ++k)
            widest =
                std::max(widest, (k + 1 < phi_.size() ? phi_[k + 1] : phi_[0] + 360) - phi_[k]);
        if (phi_.size() < 3 || widest > 2 * 360.0 / phi_.size())
            throw std::invalid_argument(
                "an anisotropic case swept at phi_i = " + list_degrees(data_.phi_i_deg) +
                " deg: a table needs phi_i around the full turn (at least 3 azimuths, no gap "
                "wider than twice 360/n)");
    } else if (phi_.size() > size_t(kMaxIsotropicSlices)) {
        phi_.resize(kMaxIsotropicSlices);
        phi_order.resize(kMaxIsotropicSlices);
    }
    max_blend_ = data_.isotropic ? 2 * int(phi_.size()) : 4;

    // Nodes: each incidence's lobe, rescaled so that its interpolant keeps the table's albedo.
    nodes_.resize(theta_.size() * phi_.size());
    for (size_t ti = 0; ti < theta_.size(); ++ti)
        for (size_t pj = 0; pj < phi_.size(); ++pj) {
            const size_t stored = theta_order[ti] * np + phi_order[pj];
            Node& n = nodes_[ti * phi_.size() + pj];
            n.f.assign(data_.f.begin() + stored * N * C, data_.f.begin() + (stored + 1) * N * C);
            // An isotropic lobe is symmetric about its plane of incidence: at phi_i = 0 or 180
            // the mirror image of cell j of a ring is cell n - 1 - j, and their mean is the
            // better estimate of both (half the variance where the lobe is even).
            if (data_.isotropic && std::fmod(phi_[pj], 180.0) == 0) {
                const std::vector<double> raw = n.f;
                for (int r = 0; r < grid_->rings(); ++r) {
                    const int first = grid_->ring_first(r), count = grid_->ring_count(r);
                    for (int j = 0; j < count; ++j)
                        for (size_t ch = 0; ch < C; ++ch)
                            n.f[size_t(first + j) * C + ch] =
                                0.5 * (raw[size_t(first + j) * C + ch] +
                                       raw[size_t(first + count - 1 - j) * C + ch]);
                }
            }
            n.albedo.assign(C, 0.0);
            n.albedo_stderr.assign(C, 0.0);
            for (size_t ch = 0; ch < C; ++ch) {
                for (size_t c = 0; c < N; ++c)
                    n.albedo[ch] += n.f[c * C + ch] * sensor_->cell(int(c)).projected_solid_angle;
                if (!data_.albedo_stderr.empty())
                    n.albedo_stderr[ch] = data_.albedo_stderr[stored * C + ch];
                const double integral = grid_->integral(n.f.data() + ch, int(C));
                if (integral > 0)
                    for (size_t c = 0; c < N; ++c) n.f[c * C + ch] *= n.albedo[ch] / integral;
            }
            std::vector<double> mean(N, 0.0);
            for (size_t c = 0; c < N; ++c)
                for (size_t ch = 0; ch < C; ++ch) mean[c] += n.f[c * C + ch] / double(C);
            n.sampler = SensorLobeSampler(*grid_, std::move(mean));
        }
}

bool BsdfTable::covers(const Vec3& wi, double tolerance_deg) const {
    const double t = degrees(spherical_theta(wi));
    return t >= theta_.front() - tolerance_deg && t <= theta_.back() + tolerance_deg;
}

int BsdfTable::blend(const Vec3& wi, Blend* out) const {
    // theta: linear between the bracketing nodes, clamped at the ends of the sweep.
    const double t = std::clamp(degrees(spherical_theta(wi)), theta_.front(), theta_.back());
    int t0 = int(std::upper_bound(theta_.begin(), theta_.end(), t) - theta_.begin()) - 1;
    t0 = std::clamp(t0, 0, int(theta_.size()) - 1);
    const int t1 = std::min(t0 + 1, int(theta_.size()) - 1);
    const double wt = t1 == t0 ? 0.0 : (t - theta_[t0]) / (theta_[t1] - theta_[t0]);
    const double phi = spherical_phi(wi);
    int count = 0;
    auto add = [&](int ti, int pj, double w, double rotation) {
        if (w > 0) out[count++] = {ti * int(phi_.size()) + pj, w, rotation};
    };
    if (data_.isotropic) {
        const double share = 1.0 / double(phi_.size());
        for (int pj = 0; pj < int(phi_.size()); ++pj) {
            const double rotation = radians(phi_[pj]) - phi;
            add(t0, pj, (1 - wt) * share, rotation);
            if (t1 != t0) add(t1, pj, wt * share, rotation);
        }
        return count;
    }
    const double p = degrees(phi);
    int p0 = int(std::upper_bound(phi_.begin(), phi_.end(), p) - phi_.begin()) - 1;
    if (p0 < 0) p0 = int(phi_.size()) - 1; // before the first azimuth: wraps from the last
    const int p1 = p0 + 1 == int(phi_.size()) ? 0 : p0 + 1;
    double gap = phi_[p1] - phi_[p0];
    double from = p - phi_[p0];
    if (gap <= 0) gap += 360;
    if (from < 0) from += 360;
    const double wp = from / gap;
    add(t0, p0, (1 - wt) * (1 - wp), 0);
    add(t0, p1, (1 - wt) * wp, 0);
    if (t1 != t0) {
        add(t1, p0, wt * (1 - wp), 0);
        add(t1, p1, wt * wp, 0);
    }
    return count;
}

Vec3 BsdfTable::to_node(const Vec3& wo, double rotation) const {
    const double c = std::cos(rotation), s = std::sin(rotation);
    return {c * wo.x - s * wo.y, s * wo.x + c * wo.y, data_.transmission ? -wo.z : wo.z};
}

namespace {
bool on_its_side(const Vec3& wi, const Vec3& wo, bool transmission) {
    return wi.z > 0 && (transmission ? wo.z < 0 : wo.z > 0);
}
} // namespace

void BsdfTable::eval(const Vec3& wi, const Vec3& wo, double* f) const {
    const int C = data_.channels;
    std::fill(f, f + C, 0.0);
    if (!on_its_side(wi, wo, data_.transmission)) return;
    std::array<Blend, kMaxBlend> b;
    const int count = blend(wi, b.data());
    for (int e = 0; e < count; ++e) {
        const Node& n = nodes_[b[e].node];
        const SensorLobeGrid::Weights w = grid_->weights(to_node(wo, b[e].rotation));
        for (int k = 0; k < w.count; ++k) {
            const double* v = n.f.data() + size_t(w.cell[k]) * C;
            const double scale = b[e].weight * w.weight[k];
            for (int ch = 0; ch < C; ++ch) f[ch] += scale * v[ch];
        }
    }
}

double BsdfTable::eval_mean(const Vec3& wi, const Vec3& wo) const {
    if (!on_its_side(wi, wo, data_.transmission)) return 0;
    std::array<Blend, kMaxBlend> b;
    const int count = blend(wi, b.data());
    double f = 0;
    for (int e = 0; e < count; ++e)
        f += b[e].weight * nodes_[b[e].node].sampler.eval(to_node(wo, b[e].rotation));
    return f;
}

bool BsdfTable::sample(const Vec3& wi, double u0, double u1, double u2, Sample& s) const {
    if (wi.z <= 0) return false;
    std::array<Blend, kMaxBlend> b;
    const int count = blend(wi, b.data());
    double total = 0;
    for (int e = 0; e < count; ++e) total += b[e].weight * nodes_[b[e].node].sampler.total();
    if (!(total > 0)) return false;
    double x = u0 * total;
    int e = 0;
    for (; e + 1 < count; ++e) {
        const double m = b[e].weight * nodes_[b[e].node].sampler.total();
        if (x < m) break;
        x -= m;
    }
    const double m = b[e].weight * nodes_[b[e].node].sampler.total();
    const double u0r = m > 0 ? std::clamp(x / m, 0.0, 0x1.fffffffffffffp-1) : 0.0;
    const Vec3 d = nodes_[b[e].node].sampler.sample(u0r, u1, u2);
    // Back from the node's frame: the inverse rotation, and the mirror for transmission.
    const double c = std::cos(b[e].rotation), sn = std::sin(b[e].rotation);
    s.wo = {c * d.x + sn * d.y, -sn * d.x + c * d.y, data_.transmission ? -d.z : d.z};
    s.pdf = pdf(wi, s.wo);
    return s.pdf > 0;
}

double BsdfTable::pdf(const Vec3& wi, const Vec3& wo) const {
    if (!on_its_side(wi, wo, data_.transmission)) return 0;
    std::array<Blend, kMaxBlend> b;
    const int count = blend(wi, b.data());
    double total = 0, density = 0;
    const double cos_o = std::abs(wo.z) / length(wo);
    for (int e = 0; e < count; ++e) {
        const SensorLobeSampler& sampler = nodes_[b[e].node].sampler;
        total += b[e].weight * sampler.total();
        density += b[e].weight * sampler.eval(to_node(wo, b[e].rotation)) * cos_o;
    }
    return total > 0 ? density / total : 0;
}

void BsdfTable::albedo(const Vec3& wi, double* a) const {
    std::fill(a, a + data_.channels, 0.0);
    if (wi.z <= 0) return;
    std::array<Blend, kMaxBlend> b;
    const int count = blend(wi, b.data());
    for (int e = 0; e < count; ++e)
        for (int ch = 0; ch < data_.channels; ++ch)
            a[ch] += b[e].weight * nodes_[b[e].node].albedo[ch];
}

double BsdfTable::node_albedo(int theta_index, int phi_index, int channel) const {
    return node(theta_index, phi_index).albedo.at(size_t(channel));
}

double BsdfTable::node_albedo_stderr(int theta_index, int phi_index, int channel) const {
    return node(theta_index, phi_index).albedo_stderr.at(size_t(channel));
}

} // namespace gonio
