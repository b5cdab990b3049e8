// gonio.run and gonio.model: the library's run_local and run_models (gonio/run/run.h) with the
// GIL released while they work. Ctrl-C (Python's SIGINT handler) is checked between incidences:
// the run stops, nothing is written, and KeyboardInterrupt is raised.
#include "bindings.h"
#include "core/threads.h"
#include "gonio/run/run.h"
#include "heightfield/surface_cache.h"

#include <Python.h>
#include <optional>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

namespace gonio::python {

namespace {
// A Python error raised inside a callback while C++ works: kept until the GIL is back.
class PendingError {
  public:
    void take() { PyErr_Fetch(&type_, &value_, &trace_); }
    bool pending() const { return type_ != nullptr; }
    [[noreturn]] void raise() {
        PyErr_Restore(type_, value_, trace_);
        type_ = value_ = trace_ = nullptr;
        throw py::error_already_set();
    }

  private:
    PyObject *type_ = nullptr, *value_ = nullptr, *trace_ = nullptr;
};

using Executor = RunResult (*)(const Config&, const RunOptions&);

std::shared_ptr<RunResult> execute(Executor executor, const Config& cfg, int threads,
                                   const py::object& progress, const py::object& cache,
                                   const std::string& command) {
    RunOptions o;
    o.threads = threads;
    o.cache = surface_cache(cache);
    o.command_line = command;
    PendingError error;
    // Called on this thread, between units: the GIL is taken back for Python's signal check.
    o.stop_requested = [&error] {
        if (error.pending()) return true;
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) error.take();
        return error.pending();
    };
    const long long total = UnitLayout(cfg).total();
    long long done = 0;
    o.observer.unit_done = [&done](const UnitId&) { ++done; };
    if (!progress.is_none())
        o.observer.started = [&](const std::string& label) {
            py::gil_scoped_acquire gil;
            if (error.pending()) return;
            try {
                progress(done, total, label);
            } catch (py::error_already_set& e) {
                e.restore();
                error.take();
            }
        };
    std::shared_ptr<RunResult> result;
    {
        const auto limit = limit_threads(threads);
        py::gil_scoped_release release;
        try {
            result = std::make_shared<RunResult>(executor(cfg, o));
        } catch (const Interrupted&) {
            // raised below, with the GIL
        }
    }
    if (error.pending()) error.raise();
    if (!result) { // interrupted, though not through Python's handler
        PyErr_SetNone(PyExc_KeyboardInterrupt);
        throw py::error_already_set();
    }
    if (!progress.is_none()) progress(total, total, "done");
    return result;
}

RunResult run_all(const Config& cfg, const RunOptions& o) {
    return run_local(cfg, o);
}
} // namespace

void bind_run(py::module_& m) {
    py::class_<RunResult, std::shared_ptr<RunResult>>(
        m, "Result", "What gonio.run or gonio.model computed (to_xarray, write)")
        .def_property_readonly("cases",
                               [](const RunResult& r) {
                                   std::vector<std::string> names;
                                   for (const CaseConfig& c : r.config.cases)
                                       names.push_back(c.name);
                                   return names;
                               })
        .def_readonly("simulated", &RunResult::simulated, "traced (run) or models only (model)")
        .def(
            "write",
            [](const RunResult& r, const py::object& path, bool overwrite) {
                const std::string file = path_of(path);
                py::gil_scoped_release release;
                write_result_file(r, file, overwrite);
            },
            py::arg("path"), py::arg("overwrite") = false,
            "Writes the HDF5 file `gonio run` would write (under a temporary name, renamed when "
            "complete)");

    const char* threads_doc = "threads: worker threads (None: every core)";
    m.def(
        "_run",
        [](const Config& cfg, std::optional<int> threads, const py::object& progress,
           const py::object& cache) {
            cfg.require_beam("gonio.run");
            return execute(&run_all, cfg, thread_count(threads), progress, cache, "gonio.run");
        },
        py::arg("config"), py::arg("threads") = py::none(), py::arg("progress") = py::none(),
        py::arg("cache") = py::none(), threads_doc);
    m.def(
        "_model",
        [](const Config& cfg, std::optional<int> threads, const py::object& progress,
           const py::object& cache) {
            return execute(&run_models, cfg, thread_count(threads), progress, cache, "gonio.model");
        },
        py::arg("config"), py::arg("threads") = py::none(), py::arg("progress") = py::none(),
        py::arg("cache") = py::none(), threads_doc);
}

} // namespace gonio::python
