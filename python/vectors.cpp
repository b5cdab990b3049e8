#include "bindings.h"

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
