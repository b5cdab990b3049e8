#include "gonio/trace/trace_backend.h"

#include <stdexcept>

namespace gonio {

const std::vector<const TraceBackendKind*>& trace_backends() {
    static const std::vector<const TraceBackendKind*> all = {&embree_backend(),
                                                             &heightfield_backend()};
    return all;
}

const TraceBackendKind& default_trace_backend() {
    return embree_backend();
}

const TraceBackendKind& trace_backend_named(const std::string& name) {
    std::string names;
    for (const TraceBackendKind* b : trace_backends()) {
        if (name == b->name) return *b;
        names += (names.empty() ? "" : ", ") + std::string(b->name);
    }
    throw std::invalid_argument("unknown trace backend '" + name + "' (allowed: " + names + ")");
}

} // namespace gonio
