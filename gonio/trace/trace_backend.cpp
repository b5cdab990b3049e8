#include "gonio/trace/trace_backend.h"

#include "core/registry.h"

#include <stdexcept>

namespace gonio {

const std::vector<const TraceBackendKind*>& trace_backends() {
    static const std::vector<const TraceBackendKind*> all = {&embree_backend(),
                                                             &heightfield_backend()};
    return all;
}

// The height field wins at every size and angle trace_bench looks at (issue 52); Embree stays the
// reference of the agreement tests.
const TraceBackendKind& default_trace_backend() {
    return heightfield_backend();
}

const TraceBackendKind& trace_backend_named(const std::string& name) {
    return find_named(trace_backends(), name, "trace backend");
}

} // namespace gonio
