// The compiled part of gonio's Python package (python/gonio/__init__.py wraps it).
#include "bindings.h"
#include "gonio_version.h"

PYBIND11_MODULE(_gonio, m) {
    m.doc() = "gonio's library, compiled (use the gonio package)";
    m.attr("__version__") = gonio::kVersion;
    gonio::python::bind_ndf(m); // before the classes that return an Ndf
    gonio::python::bind_config(m);
    gonio::python::bind_run(m);
    gonio::python::bind_models(m);
    gonio::python::bind_surface(m);
    gonio::python::bind_masking(m);
    gonio::python::bind_table(m);
}
