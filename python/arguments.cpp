// The arguments the bindings share: the surface cache, thread counts, paths, angles.
#include "bindings.h"

#include <cmath>

namespace gonio::python {

SurfaceCache surface_cache(const py::object& cache) {
    if (cache.is_none() || (py::isinstance<py::bool_>(cache) && cache.cast<bool>()))
        return SurfaceCache(default_cache_directory());
    if (py::isinstance<py::bool_>(cache)) return SurfaceCache(std::string());
    if (!py::isinstance<py::str>(cache) && !py::hasattr(cache, "__fspath__"))
        throw py::type_error("cache: None, True, False or a directory (str or os.PathLike), not " +
                             std::string(py::str(cache.get_type().attr("__name__"))));
    return SurfaceCache(path_of(cache));
}

int thread_count(std::optional<int> threads) {
    if (threads && (*threads < 0 || *threads > 1024))
        throw py::value_error("threads: " + std::to_string(*threads) +
                              " (allowed: None or 0 for every core, up to 1024)");
    return threads.value_or(0);
}

std::string path_of(const py::handle& path) {
    return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

double polar_angle(double theta_deg, const char* what) {
    if (!(theta_deg >= 0 && theta_deg < 90))
        throw py::value_error(std::string(what) + ": " + std::to_string(theta_deg) +
                              " degrees (allowed: [0, 90))");
    return theta_deg;
}

} // namespace gonio::python
