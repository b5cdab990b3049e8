// The masking measurement of an explicit surface (gonio/masking, docs/masking.md) from Python:
// gonio.masking(config), the `gonio masking` command's work and file, and Surface.masking(ndf),
// the same measurement on any one surface (a case's or a user's own height map).
#include "bindings.h"
#include "core/threads.h"
#include "gonio/masking/facet_sampler.h"
#include "gonio/masking/masking_run.h"
#include "gonio/trace/scene.h"
#include "heightfield/ndf/ndf_table.h"
#include "heightfield/ndf/tabulated_ndf.h"

#include <cmath>
#include <memory>
#include <optional>
#include <pybind11/stl.h>

namespace gonio::python {

namespace {
struct MaskingResult {
    std::shared_ptr<const Config> config;
    MaskingOptions options;
    std::vector<CaseMasking> cases;
};

MaskingOptions options_of(long long points, long long g2_points, int normal_bins, int height_bins,
                          std::optional<int> threads) {
    if (points < 1 || g2_points < 1 || normal_bins < 1 || height_bins < 1)
        throw py::value_error("masking: points, g2_points, normal_bins and height_bins must "
                              "be >= 1");
    MaskingOptions o;
    o.points = points;
    o.g2_points = g2_points;
    o.normal_bins = normal_bins;
    o.height_bins = height_bins;
    o.threads = thread_count(threads);
    return o;
}

py::tuple variable(const Array& a) {
    py::array_t<double> values(std::vector<py::ssize_t>(a.shape.begin(), a.shape.end()));
    std::copy(a.data.begin(), a.data.end(), values.mutable_data());
    return py::make_tuple(a.dims, values, a.units, a.long_name);
}

py::tuple axis(const char* name, const std::vector<double>& v, const char* units,
               const char* long_name) {
    Array a({name}, {v.size()}, units, long_name);
    a.data = v;
    return variable(a);
}

// The estimates as (coords, data variables): name -> (dims, values, units, long_name), the names
// and dims of a `gonio masking` file's case group (masking_run.cpp writes the same).
py::tuple estimates_dict(const MaskingEstimates& e) {
    py::dict coords, vars;
    std::vector<double> bins(e.bin_theta.size()), heights(e.height_edges.size() - 1);
    for (size_t k = 0; k < bins.size(); ++k) bins[k] = double(k);
    for (size_t k = 0; k < heights.size(); ++k) heights[k] = double(k);
    coords["theta_o"] = axis("theta_o", e.theta_o, "degree", "polar angle of w (G1, furnace)");
    coords["phi_o"] = axis("phi_o", e.phi_o, "degree", "azimuth of w (G1, furnace)");
    coords["normal_bin"] =
        axis("normal_bin", bins, "1", "equal-area bin of the facet normal (Beckers)");
    coords["height_bin"] = axis("height_bin", heights, "1", "quantile of the points' heights");
    coords["theta_i"] = axis("theta_i", e.theta_i, "degree", "polar angle of wi (G2)");
    coords["phi_i"] = axis("phi_i", e.phi_i, "degree", "azimuth of wi (G2)");
    coords["g2_theta_o"] = axis("g2_theta_o", e.g2_theta_o, "degree", "polar angle of wo (G2)");
    coords["g2_dphi"] = axis("g2_dphi", e.g2_dphi, "degree",
                             "azimuth of wo from phi_i (G2; 0 with theta_i: retro)");
    vars["normal_bin_theta"] =
        axis("normal_bin", e.bin_theta, "degree", "polar angle of the bin's centre");
    vars["normal_bin_phi"] = axis("normal_bin", e.bin_phi, "degree", "azimuth of the bin's centre");
    vars["height_lower_edge"] =
        axis("height_bin", std::vector<double>(e.height_edges.begin(), e.height_edges.end() - 1),
             "1", "lower edge of the height quantile");
    for (const auto& [name, a] : e.arrays) vars[py::str(name)] = variable(a);
    py::dict attrs;
    attrs["surfaces"] = e.surfaces;
    attrs["points"] = e.points;
    attrs["error_scope"] = e.surfaces > 1 ? "rays+surface" : "rays";
    return py::make_tuple(coords, vars, attrs);
}

std::shared_ptr<Ndf> facet_ndf_of(const HeightField& s) {
    return std::make_shared<TabulatedNdf>(
        facet_ndf_table(s, kFacetTable.theta_intervals, kFacetTable.phi_count), "surface",
        "height_map");
}

} // namespace

void bind_surface_masking(py::class_<Surface, std::shared_ptr<Surface>>& surface) {
    surface.def(
        "facet_ndf", [](const Surface& s) { return facet_ndf_of(s.field); },
        "The surface's own facet NDF D_s, tabulated 1 degree by 5 (what gonio masking "
        "compares Smith's forms with)");
    surface.def(
        "_masking",
        [](const Surface& s, const Ndf& ndf, const std::vector<double>& theta_i,
           const std::vector<double>& phi_i, bool isotropic, long long points, long long g2_points,
           int normal_bins, int height_bins, std::uint64_t seed, std::optional<int> threads,
           const std::string& backend) {
            const MaskingOptions o =
                options_of(points, g2_points, normal_bins, height_bins, threads);
            for (double t : theta_i) polar_angle(t, "masking(theta_i)");
            for (double p : phi_i)
                if (!std::isfinite(p)) throw py::value_error("masking(phi_i): not finite");
            const MaskingGrid grid = masking_grid(theta_i, phi_i, isotropic, o);
            const TraceBackendKind& kind =
                backend.empty() ? default_trace_backend() : trace_backend_named(backend);
            MaskingEstimates e;
            {
                const auto limit = limit_threads(o.threads);
                py::gil_scoped_release release;
                const auto facets = facet_ndf_of(s.field);
                const Scene scene(s.field, kind);
                const MaskingCounts counts = measure_masking(s.field, scene, grid, o.points,
                                                             std::min(o.points, o.g2_points), seed);
                e = estimate_masking({counts}, grid, ndf, *facets);
            }
            return estimates_dict(e);
        },
        py::arg("ndf"), py::arg("theta_i"), py::arg("phi_i"), py::arg("isotropic"),
        py::arg("points"), py::arg("g2_points"), py::arg("normal_bins"), py::arg("height_bins"),
        py::arg("seed"), py::arg("threads"), py::arg("backend"));
}

void bind_masking(py::module_& m) {
    py::class_<MaskingResult, std::shared_ptr<MaskingResult>>(
        m, "MaskingResult", "What gonio.masking measured (to_xarray, write)")
        .def_property_readonly("cases",
                               [](const MaskingResult& r) {
                                   std::vector<std::string> names;
                                   for (const CaseMasking& c : r.cases) names.push_back(c.name);
                                   return names;
                               })
        .def(
            "write",
            [](const MaskingResult& r, const py::object& path, bool overwrite) {
                const std::string file = path_of(path);
                py::gil_scoped_release release;
                write_masking_file(file, overwrite, *r.config, "gonio.masking", r.options, r.cases);
            },
            py::arg("path"), py::arg("overwrite") = false,
            "Writes the HDF5 file `gonio masking` would write (format gonio-masking 1)");
    m.def(
        "_masking",
        [](const std::shared_ptr<Config>& cfg, long long points, long long g2_points,
           int normal_bins, int height_bins, std::optional<int> threads, const py::object& cache) {
            auto r = std::make_shared<MaskingResult>();
            r->config = cfg;
            r->options = options_of(points, g2_points, normal_bins, height_bins, threads);
            const SurfaceCache store = surface_cache(cache);
            r->options.cache = &store;
            {
                const auto limit = limit_threads(r->options.threads);
                py::gil_scoped_release release;
                r->cases = run_masking(*cfg, r->options);
            }
            r->options.cache = nullptr; // `store` ends here
            return r;
        },
        py::arg("config"), py::arg("points"), py::arg("g2_points"), py::arg("normal_bins"),
        py::arg("height_bins"), py::arg("threads"), py::arg("cache"));
}

} // namespace gonio::python
