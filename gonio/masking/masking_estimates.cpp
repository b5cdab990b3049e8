#include "gonio/masking/masking_estimates.h"

#include "core/check.h"

#include <cmath>
#include <limits>

namespace gonio {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A fraction visible / front and its standard error: binomial for one surface, the spread of the
// surfaces' fractions for an ensemble (surfaces without points in the bin left out).
template <class Get>
void fraction(const std::vector<MaskingCounts>& per_surface, const MaskingCounts& all, size_t k,
              Get get, double& p, double& err) {
    const auto& [front, visible] = get(all);
    if (front[k] == 0) {
        p = err = kNaN;
        return;
    }
    p = double(visible[k]) / double(front[k]);
    err = std::sqrt(p * (1 - p) / double(front[k]));
    if (per_surface.size() < 2) return;
    double s = 0, s2 = 0;
    int n = 0;
    for (const MaskingCounts& c : per_surface) {
        const auto& [f, v] = get(c);
        if (f[k] == 0) continue;
        const double q = double(v[k]) / double(f[k]);
        s += q, s2 += q * q, ++n;
    }
    if (n < 2) return;
    const double mean = s / n, var = std::max(0.0, (s2 - n * mean * mean) / (n - 1));
    err = std::sqrt(var / n);
}

} // namespace

const Array& MaskingEstimates::operator[](const std::string& name) const {
    for (const auto& [n, a] : arrays)
        if (n == name) return a;
    GONIO_CHECK_MSG(false, "no masking array " + name);
    return arrays.front().second;
}

MaskingEstimates estimate_masking(const std::vector<MaskingCounts>& per_surface,
                                  const MaskingGrid& grid, const Ndf& target,
                                  const Ndf& facet_ndf) {
    GONIO_CHECK(!per_surface.empty());
    MaskingCounts all;
    for (const MaskingCounts& c : per_surface) all.add(c);
    const MaskingDirections dirs = masking_directions(grid);
    const BeckersSensor bins(grid.normal_bins);
    MaskingEstimates e;
    e.theta_o = grid.theta_o_deg, e.phi_o = grid.phi_o_deg;
    e.g2_theta_o = dirs.g2_theta_deg, e.g2_dphi = grid.g2_dphi_deg;
    e.theta_i = grid.theta_i_deg, e.phi_i = grid.phi_i_deg;
    for (int b = 0; b < bins.cell_count(); ++b) {
        e.bin_theta.push_back(degrees(bins.cell(b).theta_center));
        e.bin_phi.push_back(degrees(bins.cell(b).phi_center));
    }
    e.height_edges = all.height_edges;
    e.surfaces = int(per_surface.size());
    e.points = all.points;
    const size_t nt = e.theta_o.size(), np = e.phi_o.size(), nw = nt * np;
    const size_t nb = size_t(grid.normal_bins), nh = size_t(grid.height_bins);
    const size_t nti = e.theta_i.size(), npi = e.phi_i.size(), ni = nti * npi;
    const size_t n2t = e.g2_theta_o.size(), n2p = e.g2_dphi.size(), nwo = n2t * n2p;
    const std::vector<std::string> w_dims{"theta_o", "phi_o"},
        bin_dims{"theta_o", "phi_o", "normal_bin"}, h_dims{"theta_o", "phi_o", "height_bin"},
        g2_dims{"theta_i", "phi_i", "g2_theta_o", "g2_dphi"},
        g2_bin_dims{"theta_i", "phi_i", "g2_theta_o", "g2_dphi", "normal_bin"};
    auto add = [&](const std::string& name, Array a) { e.arrays.emplace_back(name, std::move(a)); };

    // G1 per normal bin and per height quantile.
    Array g1(bin_dims, {nt, np, nb}, "1",
             "measured G1(w, m): points on facets facing w that see w"),
        g1e(bin_dims, {nt, np, nb}, "1", "standard error of g1"),
        g1n(bin_dims, {nt, np, nb}, "1", "points on facets facing w (of all surfaces)");
    auto g1_counts = [](const MaskingCounts& c) { return std::tie(c.g1_front, c.g1_visible); };
    for (size_t k = 0; k < nw * nb; ++k) {
        fraction(per_surface, all, k, g1_counts, g1.data[k], g1e.data[k]);
        g1n.data[k] = double(all.g1_front[k]);
    }
    Array gh(h_dims, {nt, np, nh}, "1", "measured G1(w, height quantile)"),
        ghe(h_dims, {nt, np, nh}, "1", "standard error of g1_height");
    auto h_counts = [](const MaskingCounts& c) { return std::tie(c.g1h_front, c.g1h_visible); };
    for (size_t k = 0; k < nw * nh; ++k)
        fraction(per_surface, all, k, h_counts, gh.data[k], ghe.data[k]);

    // The furnace, the projected-area G1 and Smith's G1 from the NDF and from D_s.
    Array wf(w_dims, {nt, np}, "1",
             "weak white furnace: integral of G1(w, m) <w, m>+ D_s(m) dm (cos theta_o exactly)"),
        wfe(w_dims, {nt, np}, "1", "standard error of furnace"),
        wfz(w_dims, {nt, np}, "1", "(furnace - cos theta_o) / its standard error"),
        gp(w_dims, {nt, np}, "1", "measured G1(w) averaged over projected area"),
        gpe(w_dims, {nt, np}, "1", "standard error of g1_projected"),
        sn(w_dims, {nt, np}, "1", "Smith G1 = 1 / (1 + Lambda) of the analytic NDF [R19 Eq. 8]"),
        ss(w_dims, {nt, np}, "1", "Smith G1 = 1 / (1 + Lambda) of the surface's facet NDF D_s");
    const double n = double(all.points);
    for (size_t w = 0; w < nw; ++w) {
        const double mean = all.furnace_sum[w] / n;
        const double var = std::max(0.0, all.furnace_sum2[w] / n - mean * mean) / n;
        wf.data[w] = mean, wfe.data[w] = std::sqrt(var);
        wfz.data[w] = var > 0 ? (mean - dirs.w[w].z) / std::sqrt(var) : 0.0;
        // Ratio of sums: sum V x / sum x, x = <w, m>+ (A_micro / A_macro); delta-method error.
        const double sx = all.projected_sum[w];
        const double r = sx > 0 ? all.furnace_sum[w] / sx : kNaN;
        gp.data[w] = r;
        const double hidden2 = std::max(0.0, all.projected_sum2[w] - all.furnace_sum2[w]);
        gpe.data[w] =
            sx > 0 ? std::sqrt(all.furnace_sum2[w] * (1 - r) * (1 - r) + hidden2 * r * r) / sx
                   : kNaN;
        if (per_surface.size() >= 2) { // an ensemble: the spread of its surfaces' ratios
            double s = 0, s2 = 0;
            int m = 0;
            for (const MaskingCounts& c : per_surface) {
                if (!(c.projected_sum[w] > 0)) continue;
                const double q = c.furnace_sum[w] / c.projected_sum[w];
                s += q, s2 += q * q, ++m;
            }
            if (m >= 2)
                gpe.data[w] = std::sqrt(std::max(0.0, (s2 - m * (s / m) * (s / m)) / (m - 1)) / m);
        }
        sn.data[w] = target.G1(dirs.w[w]);
        ss.data[w] = facet_ndf.G1(dirs.w[w]);
    }

    // G2 at the incidences, per normal bin and over all facets, with Smith's three forms.
    Array g2b(g2_bin_dims, {nti, npi, n2t, n2p, nb}, "1",
              "measured G2(wi, wo, m): points on facets facing wi and wo that see both"),
        g2be(g2_bin_dims, {nti, npi, n2t, n2p, nb}, "1", "standard error of g2_bin");
    auto g2_counts = [](const MaskingCounts& c) { return std::tie(c.g2_front, c.g2_visible); };
    for (size_t k = 0; k < ni * nwo * nb; ++k)
        fraction(per_surface, all, k, g2_counts, g2b.data[k], g2be.data[k]);
    // Over the facets: the bins' counts summed.
    std::vector<MaskingCounts> summed(per_surface.size() + 1);
    auto sum_bins = [&](const MaskingCounts& c, MaskingCounts& out) {
        out.g2_front.assign(ni * nwo, 0), out.g2_visible.assign(ni * nwo, 0);
        for (size_t k = 0; k < ni * nwo * nb; ++k)
            out.g2_front[k / nb] += c.g2_front[k], out.g2_visible[k / nb] += c.g2_visible[k];
    };
    for (size_t s = 0; s < per_surface.size(); ++s) sum_bins(per_surface[s], summed[s]);
    sum_bins(all, summed.back());
    const std::vector<MaskingCounts> parts(summed.begin(), summed.end() - 1);
    Array g2(g2_dims, {nti, npi, n2t, n2p}, "1",
             "measured G2(wi, wo): points on facets facing wi and wo that see both"),
        g2e(g2_dims, {nti, npi, n2t, n2p}, "1", "standard error of g2");
    for (size_t k = 0; k < ni * nwo; ++k)
        fraction(parts, summed.back(), k, g2_counts, g2.data[k], g2e.data[k]);
    const MaskingForm forms[] = {MaskingForm::uncorrelated, MaskingForm::height_correlated,
                                 MaskingForm::height_direction_correlated};
    std::vector<Array> smith;
    for (const Ndf* ndf : {&target, &facet_ndf})
        for (MaskingForm f : forms) {
            Array a(g2_dims, {nti, npi, n2t, n2p}, "1",
                    std::string("Smith G2, ") + name_of(f) + ", Lambda of " +
                        (ndf == &target ? "the analytic NDF" : "the facet NDF D_s"));
            for (size_t i = 0; i < ni; ++i) {
                const double li = ndf->lambda(dirs.wi[i]);
                for (size_t o = 0; o < nwo; ++o) {
                    const Vec3& wo = dirs.wo[i][o];
                    a.data[i * nwo + o] = smith_g2(li, ndf->lambda(wo), dirs.wi[i], wo, f);
                }
            }
            smith.push_back(std::move(a));
        }

    add("g1", std::move(g1)), add("g1_stderr", std::move(g1e)), add("g1_points", std::move(g1n));
    add("g1_height", std::move(gh)), add("g1_height_stderr", std::move(ghe));
    add("furnace", std::move(wf)), add("furnace_stderr", std::move(wfe));
    add("furnace_z", std::move(wfz));
    add("g1_projected", std::move(gp)), add("g1_projected_stderr", std::move(gpe));
    add("g1_smith_ndf", std::move(sn)), add("g1_smith_surface", std::move(ss));
    add("g2", std::move(g2)), add("g2_stderr", std::move(g2e));
    add("g2_bin", std::move(g2b)), add("g2_bin_stderr", std::move(g2be));
    const char* suffix[] = {"uncorrelated", "height_correlated", "height_direction_correlated"};
    for (int k = 0; k < 6; ++k)
        add(std::string("g2_smith_") + suffix[k % 3] + (k < 3 ? "_ndf" : "_surface"),
            std::move(smith[size_t(k)]));
    return e;
}

} // namespace gonio
