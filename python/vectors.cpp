#include "bindings.h"

#include <algorithm>
#include <cmath>
#include <pybind11/stl.h>
#include <stdexcept>

namespace gonio::python {

Vectors vectors(const py::handle& h, int width, const char* what) {
    Vectors v;
    v.width = width;
    v.array = Doubles::ensure(h);
    if (!v.array) throw py::type_error(std::string(what) + ": not an array of numbers");
    if (v.array.ndim() < 1 || v.array.shape(v.array.ndim() - 1) != width)
        throw py::value_error(std::string(what) + ": an array of shape (..., " +
                              std::to_string(width) + ") is needed, got " +
                              std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(
                                  v.array.shape(), v.array.shape() + v.array.ndim()))))));
    v.leading.assign(v.array.shape(), v.array.shape() + v.array.ndim() - 1);
    v.count = v.array.size() / width;
    return v;
}

Vectors directions(const py::handle& h, const char* what, bool upper) {
    Vectors v = vectors(h, 3, what);
    Doubles unit(std::vector<py::ssize_t>(v.array.shape(), v.array.shape() + v.array.ndim()));
    double* out = unit.mutable_data();
    for (py::ssize_t k = 0; k < v.count; ++k) {
        const double* p = v.at(k);
        const double length = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        if (!std::isfinite(length) || !(length > 0))
            throw py::value_error(std::string(what) +
                                  ": directions must be finite and not zero (one is (" +
                                  std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " +
                                  std::to_string(p[2]) + "))");
        if (upper && !(p[2] > 0))
            throw py::value_error(std::string(what) +
                                  ": the direction must lie above the surface (z > 0)");
        // Unit vectors (to rounding) pass as they are: a sample's wo gives back its own pdf.
        const double scale = std::abs(length - 1) > 1e-12 ? 1 / length : 1.0;
        for (int c = 0; c < 3; ++c) out[3 * k + c] = p[c] * scale;
    }
    v.array = unit;
    return v;
}

Vectors uniforms(const py::handle& h, int width, const char* what) {
    Vectors v = vectors(h, width, what);
    Doubles copy(std::vector<py::ssize_t>(v.array.shape(), v.array.shape() + v.array.ndim()));
    double* out = copy.mutable_data();
    const double below_one = std::nextafter(1.0, 0.0);
    for (py::ssize_t k = 0; k < v.count * width; ++k) {
        const double u = v.array.data()[k];
        if (!(u >= 0 && u <= 1))
            throw py::value_error(std::string(what) + ": uniforms must lie in [0, 1] (one is " +
                                  std::to_string(u) + ")");
        out[k] = std::min(u, below_one); // 1 is taken as the largest double below it
    }
    v.array = copy;
    return v;
}

std::vector<py::ssize_t> broadcast(const std::vector<const Vectors*>& inputs, py::ssize_t& count,
                                   const char* what) {
    const Vectors* widest = inputs.front();
    for (const Vectors* v : inputs)
        if (!v->leading.empty()) widest = v;
    for (const Vectors* v : inputs)
        if (!v->leading.empty() && v->leading != widest->leading)
            throw py::value_error(std::string(what) +
                                  ": the arrays' shapes before the last axis differ (each must "
                                  "have the same, or be a single vector)");
    count = widest->count;
    return widest->leading;
}

Doubles new_array(const std::vector<py::ssize_t>& leading, const std::vector<py::ssize_t>& tail) {
    std::vector<py::ssize_t> shape = leading;
    shape.insert(shape.end(), tail.begin(), tail.end());
    return Doubles(shape);
}

} // namespace gonio::python
