#pragma once
// gonio's Python module (_gonio, wrapped by the package python/gonio): each file binds one part of
// the library. Directions cross as numpy arrays of shape (..., 3), evaluated in C++ without the
// GIL; results come back with the arrays' leading shape.
#include "core/math.h"
#include "gonio/config/config.h"
#include "heightfield/generate.h"
#include "heightfield/heightfield.h"
#include "heightfield/surface_cache.h"

#include <functional>
#include <memory>
#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <string>
#include <vector>

namespace gonio::python {

namespace py = pybind11;

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// An array of vectors of length `width` (the last axis): how many, and the shape before the last
// axis (empty for a single vector).
struct Vectors {
    Doubles array;
    py::ssize_t count = 0;
    std::vector<py::ssize_t> leading;
    const double* at(py::ssize_t k) const {
        return array.data() + (leading.empty() ? 0 : k * width);
    }
    int width = 3;
};
Vectors vectors(const py::handle& h, int width, const char* what);
// Directions, normalised (finite and not zero; with `upper`, above the surface: z > 0), and
// uniforms in [0, 1] (1 taken as the largest double below it): ValueError naming `what` otherwise.
Vectors directions(const py::handle& h, const char* what, bool upper = false);
Vectors uniforms(const py::handle& h, int width, const char* what);

// The common count and leading shape of several arrays of vectors: each has the same leading
// shape or is a single vector (broadcast). Throws ValueError naming `what` otherwise.
std::vector<py::ssize_t> broadcast(const std::vector<const Vectors*>& inputs, py::ssize_t& count,
                                   const char* what);

// A new array of shape leading + tail.
Doubles new_array(const std::vector<py::ssize_t>& leading, const std::vector<py::ssize_t>& tail);

// The `cache` argument: None or True the command's default directory, False none, else a path.
SurfaceCache surface_cache(const py::object& cache);
// `threads`: None or 0 every core, else 1 to 1024 (ValueError otherwise).
int thread_count(std::optional<int> threads);
// A str or os.PathLike as a path.
std::string path_of(const py::handle& path);
// A polar angle of incidence in degrees, checked to lie in [0, 90) (ValueError naming `what`).
double polar_angle(double theta_deg, const char* what);

// A case of a config: the Python object keeps its config alive.
struct CaseRef {
    std::shared_ptr<const Config> config;
    const CaseConfig* c;
};

inline Vec3 vec3(const double* p) {
    return {p[0], p[1], p[2]};
}

// A height field held by Python (gonio.Surface).
struct Surface {
    HeightField field;
    GenerationLog log;
    std::string origin;                   // "generated", "cache", "loaded", "array"
    std::vector<std::string> preparation; // a measured map's steps (map_preparation.h)
};

// Surface.masking and Surface.facet_ndf (masking_bindings.cpp).
void bind_surface_masking(py::class_<Surface, std::shared_ptr<Surface>>& surface);

void bind_config(py::module_& m);
void bind_run(py::module_& m);
void bind_ndf(py::module_& m);
void bind_models(py::module_& m);
void bind_surface(py::module_& m);
void bind_masking(py::module_& m);
void bind_table(py::module_& m);

} // namespace gonio::python
