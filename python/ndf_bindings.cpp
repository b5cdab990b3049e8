// gonio.Ndf: every distribution family, built from the same key declarations as a config's [ndf]
// table, evaluated on numpy arrays of directions.
#include "bindings.h"
#include "core/enum_names.h"
#include "heightfield/ndf/ndf_family.h"

#include <memory>
#include <pybind11/stl.h>

namespace gonio::python {

namespace {
// out[k] = f(k) over `count` items, without the GIL (the inputs are held by the caller).
template <class F>
void each(py::ssize_t count, F f) {
    py::gil_scoped_release release;
    for (py::ssize_t k = 0; k < count; ++k) f(k);
}

// A scalar per direction.
template <class F>
Doubles per_direction(const py::handle& w, const char* what, F f) {
    const Vectors v = directions(w, what);
    Doubles out = new_array(v.leading, {});
    double* o = out.mutable_data();
    each(v.count, [&](py::ssize_t k) { o[k] = f(vec3(v.at(k))); });
    return out;
}

// A scalar per pair (or triple) of directions, broadcast.
template <class F>
Doubles per_pair(const py::handle& a, const py::handle& b, const char* what, F f) {
    const Vectors va = directions(a, what), vb = directions(b, what);
    py::ssize_t count = 0;
    Doubles out = new_array(broadcast({&va, &vb}, count, what), {});
    double* o = out.mutable_data();
    each(count, [&](py::ssize_t k) { o[k] = f(vec3(va.at(k)), vec3(vb.at(k))); });
    return out;
}

py::list families() {
    py::list out;
    for (const NdfFamily* f : ndf_families()) {
        py::list keys;
        for (const Key& k : f->keys)
            keys.append(py::make_tuple(k.name, k.type_text(), k.default_text(), k.meaning));
        out.append(py::make_tuple(f->name, f->summary, keys));
    }
    return out;
}
} // namespace

void bind_ndf(py::module_& m) {
    py::class_<Ndf, std::shared_ptr<Ndf>>(m, "Ndf",
                                          "A microfacet normal distribution (gonio.ndf makes one). "
                                          "Directions are arrays of shape (..., 3), n = +z.")
        .def_property_readonly("name", &Ndf::name, "the family")
        .def("__repr__", [](const Ndf& n) { return "<gonio.Ndf " + n.describe() + ">"; })
        .def_property_readonly("description", &Ndf::describe)
        .def(
            "D",
            [](const Ndf& n, const py::handle& m) {
                return per_direction(m, "D(m)", [&](const Vec3& v) { return n.D(v); });
            },
            py::arg("m"), "D(m) in 1/sr, normalised so that the integral of D(m) m.z is 1")
        .def(
            "Lambda",
            [](const Ndf& n, const py::handle& w) {
                return per_direction(w, "Lambda(w)", [&](const Vec3& v) { return n.lambda(v); });
            },
            py::arg("w"), "Smith's Lambda(w) [R19 Eq. 8]; +inf at or below the horizon")
        .def(
            "G1",
            [](const Ndf& n, const py::handle& w, const py::object& m) {
                if (m.is_none())
                    return per_direction(w, "G1(w)", [&](const Vec3& v) { return n.G1(v); });
                return per_pair(w, m, "G1(w, m)",
                                [&](const Vec3& v, const Vec3& h) { return n.G1(v, h); });
            },
            py::arg("w"), py::arg("m") = py::none(),
            "Smith's G1(w) = 1 / (1 + Lambda(w)), or with m the masking of facet m seen from w "
            "(0 when back-facing) [R19 Eq. 4]")
        .def(
            "G2",
            [](const Ndf& n, const py::handle& wi, const py::handle& wo, const py::handle& m,
               const std::string& masking) {
                const MaskingForm form = enum_named<MaskingForm>(masking);
                const Vectors a = directions(wi, "G2(wi, wo, m)"), b = directions(wo, "G2"),
                              c = directions(m, "G2");
                py::ssize_t count = 0;
                Doubles out = new_array(broadcast({&a, &b, &c}, count, "G2(wi, wo, m)"), {});
                double* o = out.mutable_data();
                each(count, [&](py::ssize_t k) {
                    o[k] = n.G2(vec3(a.at(k)), vec3(b.at(k)), vec3(c.at(k)), form);
                });
                return out;
            },
            py::arg("wi"), py::arg("wo"), py::arg("m"), py::arg("masking") = "height-correlated",
            "Masking-shadowing G2(wi, wo, m): height-correlated [R19 Eq. 9], uncorrelated "
            "[R19 Eq. 3], v-cavity [M18 Eq. 15] or height-direction-correlated")
        .def(
            "pdf",
            [](const Ndf& n, const py::handle& m) {
                return per_direction(m, "pdf(m)", [&](const Vec3& v) { return n.pdf_m(v); });
            },
            py::arg("m"), "the density of sample: D(m) m.z")
        .def(
            "pdf_visible",
            [](const Ndf& n, const py::handle& w, const py::handle& m) {
                return per_pair(w, m, "pdf_visible(w, m)",
                                [&](const Vec3& v, const Vec3& h) { return n.pdf_visible(v, h); });
            },
            py::arg("w"), py::arg("m"),
            "the density of sample_visible: G1(w, m) <w.m> D(m) / w.z [Heitz 2014]")
        .def(
            "sample",
            [](const Ndf& n, const py::handle& u) {
                const Vectors uv = uniforms(u, 2, "sample(u)");
                Doubles out = new_array(uv.leading, {3});
                double* o = out.mutable_data();
                each(uv.count, [&](py::ssize_t k) {
                    const Vec3 s = n.sample_m(uv.at(k)[0], uv.at(k)[1]);
                    o[3 * k] = s.x, o[3 * k + 1] = s.y, o[3 * k + 2] = s.z;
                });
                return out;
            },
            py::arg("u"), "normals with density D(m) m.z from uniforms u of shape (..., 2)")
        .def(
            "sample_visible",
            [](const Ndf& n, const py::handle& w, const py::handle& u) {
                const Vectors wv = directions(w, "sample_visible(w, u)", true),
                              uv = uniforms(u, 2, "sample_visible(w, u)");
                py::ssize_t count = 0;
                Doubles out = new_array(broadcast({&wv, &uv}, count, "sample_visible(w, u)"), {3});
                double* o = out.mutable_data();
                each(count, [&](py::ssize_t k) {
                    const Vec3 s = n.sample_visible(vec3(wv.at(k)), uv.at(k)[0], uv.at(k)[1]);
                    o[3 * k] = s.x, o[3 * k + 1] = s.y, o[3 * k + 2] = s.z;
                });
                return out;
            },
            py::arg("w"), py::arg("u"),
            "normals visible from w (w.z > 0) with density pdf_visible, from uniforms u of shape "
            "(..., 2) [Heitz 2014]");

    m.def(
        "_ndf_from_toml",
        [](const std::string& text) { return std::shared_ptr<Ndf>(ndf_from_toml(text)); },
        py::arg("table"));
    m.def("_ndf_families", &families);
    m.def("_masking_forms", &enum_names<MaskingForm>);
}

} // namespace gonio::python
