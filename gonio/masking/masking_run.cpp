#include "gonio/masking/masking_run.h"

#include "core/float_mode.h"
#include "core/threads.h"
#include "gonio/io/result_writer.h"
#include "gonio/io/sealed_file.h"
#include "gonio/masking/facet_sampler.h"
#include "gonio/table/result_case.h"
#include "gonio/trace/scene.h"
#include "heightfield/ndf/ndf_table.h"
#include "heightfield/ndf/tabulated_ndf.h"
#include "heightfield/surface_source.h"

#include <hdf5_hl.h>

namespace gonio {

MaskingGrid masking_grid(const std::vector<double>& theta_i_deg,
                         const std::vector<double>& phi_i_deg, bool isotropic,
                         const MaskingOptions& o) {
    MaskingGrid g;
    for (int t = 0; t <= 80; t += 10) g.theta_o_deg.push_back(t);
    g.theta_o_deg.push_back(85), g.theta_o_deg.push_back(89);
    if (isotropic)
        g.phi_o_deg = {0};
    else
        for (int p = 0; p < 360; p += 45) g.phi_o_deg.push_back(p);
    g.normal_bins = o.normal_bins;
    g.height_bins = o.height_bins;
    g.theta_i_deg = theta_i_deg;
    g.phi_i_deg = theta_i_deg.empty() ? std::vector<double>{} : phi_i_deg;
    for (int t = 0; t <= 80; t += 10) g.g2_theta_o_deg.push_back(t);
    g.g2_theta_o_deg.push_back(85);
    for (int p = 0; p < 360; p += 30) g.g2_dphi_deg.push_back(p);
    return g;
}

MaskingGrid masking_grid(const CaseConfig& c, const MaskingOptions& o) {
    return masking_grid(c.theta_i_deg, c.phi_i_deg, case_is_isotropic(c), o);
}

std::vector<CaseMasking> run_masking(const Config& cfg, const MaskingOptions& o) {
    const ResultFloatMode float_mode;
    std::vector<CaseMasking> out;
    for (const CaseConfig& c : cfg.cases) {
        const MaskingGrid grid = masking_grid(c, o);
        std::vector<MaskingCounts> counts;
        std::unique_ptr<Ndf> facet_ndf;
        CaseMasking m;
        m.name = c.name;
        m.ndf = c.ndf->describe();
        const int surfaces = c.surface.realisations;
        for (int r = 0; r < surfaces; ++r) {
            SurfaceOrigin origin;
            const SurfaceCache none("");
            const HeightField s = obtain_surface(*c.ndf, realisation(c.surface, r),
                                                 o.cache ? *o.cache : none, o.threads, origin);
            if (r == 0) {
                m.surface = origin.loaded ? c.surface.input : origin.cache_path;
                if (surfaces > 1)
                    m.surface = "an ensemble of " + std::to_string(surfaces) +
                                " surfaces, the first " + m.surface;
                // D_s of the first surface: the default table of the height_map family.
                facet_ndf = std::make_unique<TabulatedNdf>(
                    facet_ndf_table(s, kFacetTable.theta_intervals, kFacetTable.phi_count),
                    c.name + " surface", "height_map");
            }
            const Scene scene(s, *c.trace.backend);
            counts.push_back(
                measure_masking(s, scene, grid, o.points, std::min(o.points, o.g2_points),
                                cfg.seed ^ (std::uint64_t(r + 1) << 40), [&](double f) {
                                    if (o.progress)
                                        o.progress(c.name + " surface " + std::to_string(r + 1) +
                                                       "/" + std::to_string(surfaces),
                                                   (r + f) / surfaces);
                                }));
        }
        m.estimates = estimate_masking(counts, grid, *c.ndf, *facet_ndf);
        out.push_back(std::move(m));
    }
    return out;
}

namespace {

struct Group {
    h5::Handle group;
    std::map<std::string, h5::Handle> scales;

    void scale(const std::string& name, const std::vector<double>& v, const std::string& units,
               const std::string& long_name, bool integer = false) {
        scales[name] = h5::write_scale(group, name, v, units, long_name, integer);
    }
    void put(const std::string& name, const Array& a) {
        std::vector<hsize_t> dims(a.shape.begin(), a.shape.end()), chunk = dims;
        for (hsize_t& c : chunk) c = std::max<hsize_t>(c, 1);
        const h5::Handle d =
            h5::write_dataset(group, name, dims, chunk, a.data.data(), a.units, a.long_name);
        for (size_t k = 0; k < a.rank(); ++k)
            h5::check(H5DSattach_scale(d, scales.at(a.dims[k]), unsigned(k)),
                      ("attach " + a.dims[k] + " to " + name).c_str());
    }
};

} // namespace

void write_masking_file(const std::string& path, bool overwrite, const Config& cfg,
                        const std::string& command_line, const MaskingOptions& o,
                        const std::vector<CaseMasking>& cases) {
    SealedFile file(path, overwrite, "a masking file");
    write_provenance(file, "gonio-masking 1", cfg, command_line);
    h5::write_int_attribute(file, "points_per_surface", o.points);
    h5::write_int_attribute(file, "g2_points_per_surface", std::min(o.points, o.g2_points));
    std::vector<std::string> names;
    for (const CaseMasking& c : cases) names.push_back(c.name);
    h5::write_string_list_attribute(file, "cases", names);
    for (const CaseMasking& c : cases) {
        const MaskingEstimates& e = c.estimates;
        Group g{h5::Handle(H5Gcreate2(file, c.name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                           H5Gclose, ("create group " + c.name).c_str()),
                {}};
        h5::write_string_attribute(g.group, "ndf", c.ndf);
        h5::write_string_attribute(g.group, "surface", c.surface);
        h5::write_int_attribute(g.group, "surfaces", e.surfaces);
        h5::write_string_attribute(g.group, "error_scope",
                                   e.surfaces > 1 ? "rays+surface" : "rays");
        g.scale("theta_o", e.theta_o, "degree", "polar angle of w (G1, furnace)");
        g.scale("phi_o", e.phi_o, "degree", "azimuth of w (G1, furnace)");
        std::vector<double> index(e.bin_theta.size()), hb(e.height_edges.size() - 1);
        for (size_t k = 0; k < index.size(); ++k) index[k] = double(k);
        for (size_t k = 0; k < hb.size(); ++k) hb[k] = double(k);
        g.scale("normal_bin", index, "1", "equal-area bin of the facet normal (Beckers)", true);
        g.scale("height_bin", hb, "1", "quantile of the points' heights", true);
        g.scale("theta_i", e.theta_i, "degree", "polar angle of wi (G2)");
        g.scale("phi_i", e.phi_i, "degree", "azimuth of wi (G2)");
        g.scale("g2_theta_o", e.g2_theta_o, "degree", "polar angle of wo (G2)");
        g.scale("g2_dphi", e.g2_dphi, "degree",
                "azimuth of wo from phi_i (G2; 0 with theta_i: retro)");
        // The bins' and quantiles' coordinates.
        Array bt({"normal_bin"}, {e.bin_theta.size()}, "degree", "polar angle of the bin's centre");
        bt.data = e.bin_theta;
        Array bp({"normal_bin"}, {e.bin_phi.size()}, "degree", "azimuth of the bin's centre");
        bp.data = e.bin_phi;
        Array he({"height_bin"}, {hb.size()}, "1", "lower edge of the height quantile");
        he.data.assign(e.height_edges.begin(), e.height_edges.end() - 1);
        g.put("normal_bin_theta", bt);
        g.put("normal_bin_phi", bp);
        g.put("height_lower_edge", he);
        for (const auto& [name, a] : e.arrays) g.put(name, a);
    }
    file.commit();
}

} // namespace gonio
