// gonio.surface(case).generate() and gonio.surface_from_array(): height fields as numpy arrays
// (float32, shape (n, n), row y, column x) that share the surface's memory, with the fidelity
// metrics of heightfield/surface_metrics.h.
#include "bindings.h"
#include "core/threads.h"
#include "heightfield/measured/surface_character.h"
#include "heightfield/surface_metrics.h"
#include "heightfield/surface_source.h"

#include <cmath>
#include <memory>
#include <optional>
#include <pybind11/stl.h>

namespace gonio::python {

namespace {
struct SurfaceMaker {
    CaseRef ref;
};

py::dict metrics_of(const Surface& s, const Ndf& ndf, int bins) {
    SurfaceMetrics m;
    {
        py::gil_scoped_release release;
        m = measure_surface(s.field, ndf, bins);
    }
    py::dict d;
    d["ndf_distance"] = m.ndf_distance;
    d["ndf_bins"] = m.ndf_bins;
    d["alpha_eff"] = py::make_tuple(m.alpha_eff_x, m.alpha_eff_y);
    d["alpha_rms"] = py::make_tuple(m.alpha_rms_x, m.alpha_rms_y);
    d["target_alpha"] = py::make_tuple(m.target_alpha_x, m.target_alpha_y);
    d["height_rms"] = m.height_rms;
    d["height_range"] = py::make_tuple(m.height_min, m.height_max);
    d["correlation_length"] = py::make_tuple(m.correlation_length_x, m.correlation_length_y);
    return d;
}

py::dict fit_of(const AnalyticFit& f) {
    py::dict d;
    d["family"] = f.family;
    d["alpha"] = f.isotropic() ? py::object(py::float_(f.alpha_x))
                               : py::object(py::make_tuple(f.alpha_x, f.alpha_y));
    d["distance"] = f.distance;
    d["at_bound"] = f.at_lowest    ? py::object(py::str("lowest"))
                    : f.at_highest ? py::object(py::str("highest"))
                                   : py::object(py::none());
    d["ndf"] = f.ndf_toml();
    return d;
}

py::dict character_of(const Surface& s, int bins) {
    if (bins < 2 || bins > 1000000) throw py::value_error("character: bins must be in [2, 1e6]");
    SurfaceCharacter c;
    {
        py::gil_scoped_release release;
        c = characterise_surface(s.field, bins);
    }
    py::dict d;
    d["alpha_principal"] = py::make_tuple(c.alpha_major, c.alpha_minor);
    d["major_axis_deg"] = c.major_axis_deg;
    d["correlation_length"] = py::make_tuple(c.correlation_x, c.correlation_y);
    d["correlation_capped"] = py::make_tuple(c.correlation_x_capped, c.correlation_y_capped);
    d["lowest_alpha"] = c.lowest_alpha;
    d["unresolved"] = c.unresolved;
    if (!c.unresolved) {
        py::dict fits;
        fits["ggx"] = fit_of(c.ggx), fits["beckmann"] = fit_of(c.beckmann);
        fits["ggx_xy"] = fit_of(c.ggx_xy), fits["beckmann_xy"] = fit_of(c.beckmann_xy);
        d["fits"] = fits;
        d["closest"] = fit_of(c.best_xy());
    }
    d["lines"] = c.lines();
    return d;
}

std::shared_ptr<Surface> generate(const SurfaceMaker& maker, std::optional<int> threads,
                                  const py::object& cache) {
    const CaseConfig& c = *maker.ref.c;
    const SurfaceCache store = surface_cache(cache);
    auto s = std::make_shared<Surface>();
    {
        const auto limit = limit_threads(thread_count(threads));
        py::gil_scoped_release release;
        SurfaceOrigin origin;
        // Realisation 0: the surface `gonio run` traces first (the only one without an ensemble).
        s->field = obtain_surface(*c.ndf, realisation(c.surface, 0), store,
                                  worker_threads(thread_count(threads)), origin);
        s->log = origin.log;
        s->origin = origin.loaded ? "loaded" : origin.from_cache ? "cache" : "generated";
        s->preparation = origin.preparation;
    }
    return s;
}
} // namespace

void bind_surface(py::module_& m) {
    py::class_<Surface, std::shared_ptr<Surface>> surface(
        m, "Surface", "A periodic height field: n x n heights, `spacing` apart");
    surface
        .def_property_readonly(
            "heights",
            [](const std::shared_ptr<Surface>& s) -> py::array_t<float> {
                const py::ssize_t n = s->field.n, size = sizeof(float);
                // The surface's own memory: the array keeps the Surface alive.
                py::array_t<float> view(std::vector<py::ssize_t>{n, n},
                                        std::vector<py::ssize_t>{n * size, size}, s->field.h.data(),
                                        py::cast(s));
                // Read-only: the surface's metrics and traversals rely on its heights as made.
                view.attr("setflags")(py::arg("write") = false);
                return view;
            },
            "heights[y, x], float32, a read-only view of the surface's memory (no copy)")
        .def_property_readonly("n", [](const Surface& s) { return s.field.n; })
        .def_property_readonly("spacing", [](const Surface& s) { return s.field.spacing; })
        .def_property_readonly(
            "origin", [](const Surface& s) { return s.origin; },
            "generated, cache, loaded (surface.input) or array")
        .def_property_readonly(
            "generation",
            [](const Surface& s) {
                py::dict d;
                d["iterations"] = s.log.iterations;
                d["seconds"] = s.log.seconds;
                d["schwarz_mean"] = s.log.schwarz_mean;
                d["converged_early"] = s.log.converged_early;
                return d;
            },
            "the generator's log: iterations, time, mean Schwarz error per iteration")
        .def(
            "metrics",
            [](const Surface& s, const Ndf& ndf, int bins) { return metrics_of(s, ndf, bins); },
            py::arg("ndf"), py::arg("bins") = 1000,
            "Fidelity to a distribution: TV distance of the facet normals to D(m) cos(theta_m) "
            "on `bins` equal-area cells, effective roughness, height statistics, correlation "
            "lengths")
        .def_property_readonly(
            "preparation", [](const Surface& s) { return s.preparation; },
            "a measured map's preparation, one line per step as gonio surface prints it (read, "
            "missing, spikes, levelled, high-pass, filled, cropped); empty otherwise")
        .def("character", &character_of, py::arg("bins") = 1000,
             "What the surface is in the analytic models' terms (docs/measured-surfaces.md): "
             "principal slopes and axis, correlation lengths, and the closest GGX and Beckmann "
             "(isotropic and along x and y) by TV distance on `bins` equal-area cells; no "
             "`fits` when it is smoother than the cells resolve")
        .def("__repr__", [](const Surface& s) {
            return "<gonio.Surface " + std::to_string(s.field.n) + "^2, spacing " +
                   py::str(py::float_(s.field.spacing)).cast<std::string>() + ", " + s.origin + ">";
        });

    bind_surface_masking(surface);

    py::class_<SurfaceMaker>(m, "SurfaceMaker", "A case's surface, to generate (gonio.surface)")
        .def("generate", &generate, py::arg("threads") = py::none(), py::arg("cache") = py::none(),
             "The case's surface as `gonio run` traces it (realisation 0), through the surface "
             "cache unless cache=False (cache=PATH: that directory)");
    m.def(
        "surface", [](const CaseRef& r) { return SurfaceMaker{r}; }, py::arg("case"),
        "The surface of a case (gonio.Config.cases[k]): .generate() makes it");
    m.def(
        "surface_from_array",
        [](const py::handle& values, double spacing) {
            using Floats = py::array_t<float, py::array::c_style | py::array::forcecast>;
            const Floats heights = Floats::ensure(values);
            if (!heights)
                throw py::type_error("surface_from_array: heights must be an array of numbers");
            if (heights.ndim() != 2 || heights.shape(0) != heights.shape(1) || heights.shape(0) < 2)
                throw py::value_error("surface_from_array: a square array of heights of shape "
                                      "(n, n), n >= 2, is needed");
            if (!(spacing > 0) || !std::isfinite(spacing))
                throw py::value_error("surface_from_array: spacing must be finite and > 0");
            auto s = std::make_shared<Surface>();
            s->field = HeightField(int(heights.shape(0)), spacing);
            std::copy(heights.data(), heights.data() + heights.size(), s->field.h.begin());
            for (float v : s->field.h)
                if (!std::isfinite(v))
                    throw py::value_error("surface_from_array: the heights must be finite");
            s->origin = "array";
            return s;
        },
        py::arg("heights"), py::arg("spacing") = 1.0,
        "A periodic surface of one's own: heights[y, x] (copied as float32), `spacing` apart");
}

} // namespace gonio::python
