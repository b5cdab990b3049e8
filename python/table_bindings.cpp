// gonio.BsdfTable (gonio/table/bsdf_table.h: the tabulated BSDF of a simulated case, with eval,
// importance sampling and its pdf) on numpy arrays of directions, and the exports of
// `gonio export` as functions.
#include "bindings.h"
#include "core/enum_names.h"
#include "gonio/export/export.h"
#include "gonio/table/bsdf_table.h"
#include "gonio/table/result_case.h"

#include <memory>
#include <pybind11/stl.h>

namespace gonio::python {

namespace {
// Per-channel values f(wi, wo), broadcast.
template <class F>
Doubles per_pair_channels(const BsdfTable& t, const py::handle& wi, const py::handle& wo,
                          const char* what, F f) {
    const Vectors a = directions(wi, what), b = directions(wo, what);
    py::ssize_t count = 0;
    const int channels = t.channels();
    Doubles out = new_array(broadcast({&a, &b}, count, what), {channels});
    double* o = out.mutable_data();
    py::gil_scoped_release release;
    for (py::ssize_t k = 0; k < count; ++k) f(vec3(a.at(k)), vec3(b.at(k)), o + k * channels);
    return out;
}

std::shared_ptr<BsdfTable> from_result(const std::string& path, const std::string& case_name,
                                       const std::string& order, const std::string& model) {
    py::gil_scoped_release release;
    const ResultCase c = read_result_case(path, case_name);
    TableData data =
        model.empty() ? table_data(c, enum_named<TableOrder>(order)) : model_table_data(c, model);
    return std::make_shared<BsdfTable>(std::move(data));
}
} // namespace

void bind_table(py::module_& m) {
    py::class_<BsdfTable, std::shared_ptr<BsdfTable>>(
        m, "BsdfTable",
        "The tabulated BSDF of a simulated case [R19 section 4]: f(wi, wo) interpolated across the "
        "sensor and the incidences, keeping each incidence's albedo; sampled exactly by its pdf. "
        "Directions are arrays of shape (..., 3), n = +z; wi above the surface.")
        .def_property_readonly("channels", &BsdfTable::channels)
        .def_property_readonly("isotropic", &BsdfTable::isotropic)
        .def_property_readonly("transmission", &BsdfTable::transmission,
                               "the lobe lies below the surface (order 't')")
        .def_property_readonly("theta_nodes", &BsdfTable::theta_nodes,
                               "the swept theta_i (degrees)")
        .def_property_readonly("phi_nodes", &BsdfTable::phi_nodes, "the swept phi_i (degrees)")
        .def(
            "eval",
            [](const BsdfTable& t, const py::handle& wi, const py::handle& wo) {
                directions(wi, "eval(wi, wo)", true); // wi above the surface
                return per_pair_channels(
                    t, wi, wo, "eval(wi, wo)",
                    [&](const Vec3& i, const Vec3& o, double* f) { t.eval(i, o, f); });
            },
            py::arg("wi"), py::arg("wo"),
            "f(wi, wo) in 1/sr per channel (shape (..., channels)), without the cosine; 0 on "
            "the other side of the surface")
        .def(
            "pdf",
            [](const BsdfTable& t, const py::handle& wi, const py::handle& wo) {
                const Vectors a = directions(wi, "pdf(wi, wo)", true),
                              b = directions(wo, "pdf(wi, wo)");
                py::ssize_t count = 0;
                Doubles out = new_array(broadcast({&a, &b}, count, "pdf(wi, wo)"), {});
                double* o = out.mutable_data();
                py::gil_scoped_release release;
                for (py::ssize_t k = 0; k < count; ++k) o[k] = t.pdf(vec3(a.at(k)), vec3(b.at(k)));
                return out;
            },
            py::arg("wi"), py::arg("wo"),
            "the solid-angle density of sample(wi, u) at wo: proportional to the channels' mean "
            "of f times |cos theta_o|")
        .def(
            "sample",
            [](const BsdfTable& t, const py::handle& wi, const py::handle& u) {
                const Vectors a = directions(wi, "sample(wi, u)", true),
                              b = uniforms(u, 3, "sample(wi, u)");
                py::ssize_t count = 0;
                const auto leading = broadcast({&a, &b}, count, "sample(wi, u)");
                Doubles wo = new_array(leading, {3}), pdf = new_array(leading, {});
                double *w = wo.mutable_data(), *p = pdf.mutable_data();
                {
                    py::gil_scoped_release release;
                    for (py::ssize_t k = 0; k < count; ++k) {
                        const double* v = b.at(k);
                        BsdfTable::Sample s;
                        if (!t.sample(vec3(a.at(k)), v[0], v[1], v[2], s)) s = {};
                        w[3 * k] = s.wo.x, w[3 * k + 1] = s.wo.y, w[3 * k + 2] = s.wo.z;
                        p[k] = s.pdf;
                    }
                }
                return py::make_tuple(wo, pdf);
            },
            py::arg("wi"), py::arg("u"),
            "(wo, pdf) from uniforms u in [0, 1) of shape (..., 3); wo = 0 and pdf = 0 where the "
            "lobe is empty")
        .def(
            "albedo",
            [](const BsdfTable& t, const py::handle& wi) {
                const Vectors a = directions(wi, "albedo(wi)", true);
                Doubles out = new_array(a.leading, {t.channels()});
                double* o = out.mutable_data();
                py::gil_scoped_release release;
                for (py::ssize_t k = 0; k < a.count; ++k)
                    t.albedo(vec3(a.at(k)), o + k * t.channels());
                return out;
            },
            py::arg("wi"), "the integral of f |cos theta_o| over wo, per channel (exact)")
        .def("__repr__", [](const BsdfTable& t) {
            return "<gonio.BsdfTable " + std::to_string(t.theta_nodes().size()) + " x " +
                   std::to_string(t.phi_nodes().size()) + " incidences, " +
                   std::to_string(t.channels()) + " channel(s)" +
                   (t.transmission() ? ", transmission" : "") + ">";
        });
    m.def("_table_from_result", &from_result, py::arg("path"), py::arg("case"), py::arg("order"),
          py::arg("model"));

    m.def("_export_formats", [] {
        py::list out;
        for (const ExportFormat* f : export_formats())
            out.append(py::make_tuple(f->name, f->summary, f->rgb_option, f->sweep_option));
        return out;
    });
    m.def(
        "_export",
        [](const std::string& input, const std::string& format, const std::string& output,
           const std::string& case_name, const std::string& order, bool rgb,
           const std::string& sweep, bool overwrite) {
            ExportOptions o;
            o.input = input;
            o.format = &export_format_named(format);
            o.output = output;
            o.case_name = case_name;
            o.orders = enum_named<TableOrder>(order);
            o.rgb = rgb;
            o.sweep = sweep;
            o.overwrite = overwrite;
            o.quiet = true;
            ExportReport r;
            {
                py::gil_scoped_release release;
                check_export_options(o);
                r = export_result(o);
            }
            py::dict d;
            d["output"] = r.output;
            d["bytes"] = r.bytes;
            d["seconds"] = r.seconds;
            d["notes"] = r.notes;
            return d;
        },
        py::arg("input"), py::arg("format"), py::arg("output"), py::arg("case"), py::arg("order"),
        py::arg("rgb"), py::arg("sweep"), py::arg("overwrite"));
    py::register_exception<ExportRefused>(m, "ExportRefused", PyExc_ValueError);
}

} // namespace gonio::python
