#include "bindings.h"

namespace gonio::python {

SurfaceCache surface_cache(const py::object& cache) {
    if (cache.is_none() || (py::isinstance<py::bool_>(cache) && cache.cast<bool>()))
        return SurfaceCache(default_cache_directory());
    if (py::isinstance<py::bool_>(cache)) return SurfaceCache(std::string());
    return SurfaceCache(py::str(cache).cast<std::string>());
}

} // namespace gonio::python
