// gonio.model_l1(case): Model L1 [R19 Eq. 2] with the case's distribution, facets and masking,
// evaluated on arrays of directions or integrated over the case's sensor cells as `gonio run`
// integrates it.
#include "bindings.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/microfacet_model.h"
#include "sensor/beckers_sensor.h"

#include <cmath>
#include <pybind11/stl.h>

namespace gonio::python {

namespace {
struct ModelL1 {
    CaseRef ref;
    MicrofacetModel model;
    explicit ModelL1(const CaseRef& r)
        : ref(r), model(*r.c->ndf, r.c->material.fresnel, r.c->model.masking) {}
};

ModelL1 model_of(const CaseRef& r) {
    if (r.c->material.diffuse)
        throw py::value_error("case " + r.c->name + ": Model L1 is specular; its facets are " +
                              r.c->material.type +
                              " (the interfaced Lambertian model is not "
                              "bound to Python yet)");
    return ModelL1(r);
}

// f(i, o) (or f cos theta_o) per channel, broadcast over the arrays of directions.
Doubles evaluate(const ModelL1& m, const py::handle& wi, const py::handle& wo, bool cosine) {
    const Vectors a = directions(wi, "eval(wi, wo)"), b = directions(wo, "eval(wi, wo)");
    py::ssize_t count = 0;
    const int channels = m.model.channels();
    Doubles out = new_array(broadcast({&a, &b}, count, "eval(wi, wo)"), {channels});
    double* o = out.mutable_data();
    py::gil_scoped_release release;
    for (py::ssize_t k = 0; k < count; ++k) {
        if (cosine)
            m.model.eval_cosine(vec3(a.at(k)), vec3(b.at(k)), o + k * channels);
        else
            m.model.eval(vec3(a.at(k)), vec3(b.at(k)), o + k * channels);
    }
    return out;
}
} // namespace

void bind_models(py::module_& m) {
    py::class_<ModelL1>(m, "ModelL1",
                        "Model L1 of a case: the specular microfacet BRDF with Smith masking "
                        "[R19 Eq. 2]")
        .def_property_readonly("channels", [](const ModelL1& l) { return l.model.channels(); })
        .def(
            "eval",
            [](const ModelL1& l, const py::handle& wi, const py::handle& wo) {
                return evaluate(l, wi, wo, false);
            },
            py::arg("wi"), py::arg("wo"),
            "f(wi, wo) in 1/sr, shape (..., channels); 0 at or below the horizon")
        .def(
            "eval_cosine",
            [](const ModelL1& l, const py::handle& wi, const py::handle& wo) {
                return evaluate(l, wi, wo, true);
            },
            py::arg("wi"), py::arg("wo"), "f(wi, wo) cos(theta_o), shape (..., channels)")
        .def(
            "cells",
            [](const ModelL1& l, double theta_i, double phi_i, std::optional<int> cells) {
                polar_angle(theta_i, "cells(theta_i)");
                if (!std::isfinite(phi_i)) throw py::value_error("cells(phi_i): not finite");
                if (cells && (*cells < 1 || *cells > 1000000))
                    throw py::value_error("cells: " + std::to_string(*cells) +
                                          " (allowed: 1 to 10^6)");
                const BeckersSensor sensor(cells.value_or(l.ref.c->sensor_cells));
                const Vec3 wi = spherical_direction(radians(theta_i), radians(phi_i));
                std::vector<double> energy;
                {
                    py::gil_scoped_release release;
                    energy = model_cell_energy(l.model, wi, sensor, l.ref.c->model.quadrature);
                }
                const int channels = l.model.channels();
                const std::vector<double> area = sensor.projected_solid_angles();
                Doubles out({py::ssize_t(sensor.cell_count()), py::ssize_t(channels)});
                double* o = out.mutable_data();
                for (size_t k = 0; k < energy.size(); ++k)
                    o[k] = energy[k] / area[k / size_t(channels)];
                return out;
            },
            py::arg("theta_i"), py::arg("phi_i") = 0.0, py::arg("cells") = py::none(),
            "The model averaged over each sensor cell (1/sr, shape (cells, channels)), with the "
            "case's quadrature: the `gonio run` file's model values at that incidence");
    m.def("model_l1", &model_of, py::arg("case"),
          "Model L1 of a case (gonio.Config.cases[k]): its distribution, facets and masking");
}

} // namespace gonio::python
