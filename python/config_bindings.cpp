// gonio.Config and gonio.Case: a config loaded and validated by the library (load_config), its
// errors raised as gonio.ConfigError with the file, line and key.
#include "bindings.h"
#include "core/config_error.h"
#include "gonio/config/config.h"

#include <memory>
#include <pybind11/stl.h>

namespace gonio::python {

void bind_config(py::module_& m) {
    py::register_exception<ConfigError>(m, "ConfigError", PyExc_ValueError);

    py::class_<CaseRef>(m, "Case", "One case of a config (gonio.Config.cases)")
        .def_property_readonly("name", [](const CaseRef& r) { return r.c->name; })
        .def_property_readonly(
            "ndf", [](const CaseRef& r) { return std::const_pointer_cast<Ndf>(r.c->ndf); },
            "the case's distribution, as gonio.ndf makes it")
        .def_property_readonly(
            "theta_i", [](const CaseRef& r) { return r.c->theta_i_deg; },
            "incidence polar angles, degrees")
        .def_property_readonly(
            "phi_i", [](const CaseRef& r) { return r.c->phi_i_deg; }, "incidence azimuths, degrees")
        .def_property_readonly(
            "cells", [](const CaseRef& r) { return r.c->sensor_cells; },
            "sensor cells per hemisphere")
        .def_property_readonly("channels", [](const CaseRef& r) { return r.c->channels(); })
        .def_property_readonly("material",
                               [](const CaseRef& r) { return r.c->material.description; })
        .def_property_readonly("rays", [](const CaseRef& r) { return r.c->trace.rays; })
        .def_property_readonly("surface_size", [](const CaseRef& r) { return r.c->surface.size; })
        .def("__repr__", [](const CaseRef& r) {
            return "<gonio.Case " + r.c->name + ": " + r.c->ndf->describe() + ", " +
                   r.c->material.description + ">";
        });

    py::class_<Config, std::shared_ptr<Config>>(
        m, "Config", "A validated gonio config (Config.load, Config.from_toml)")
        .def_static(
            "_load",
            [](const std::string& path, const std::vector<std::string>& overrides) {
                return std::make_shared<Config>(load_config(path, overrides));
            },
            py::arg("path"), py::arg("overrides"))
        .def_static(
            "_parse",
            [](const std::string& text, const std::string& path,
               const std::vector<std::string>& overrides) {
                return std::make_shared<Config>(parse_config(text, path, overrides));
            },
            py::arg("text"), py::arg("path"), py::arg("overrides"))
        .def_readonly("path", &Config::path, "the config file as given")
        .def_readonly("seed", &Config::seed)
        .def_readonly("overrides", &Config::overrides, "the assignments applied, in order")
        .def_readonly("toml", &Config::effective_toml,
                      "the document after overrides, re-serialised")
        .def_property_readonly(
            "cases",
            [](const std::shared_ptr<Config>& c) {
                std::vector<CaseRef> out;
                for (const CaseConfig& k : c->cases) out.push_back({c, &k});
                return out;
            },
            "the cases, in config order")
        .def("__repr__", [](const Config& c) {
            std::string names;
            for (const CaseConfig& k : c.cases) names += (names.empty() ? "" : ", ") + k.name;
            return "<gonio.Config " + c.path + ": " + names + ">";
        });
}

} // namespace gonio::python
