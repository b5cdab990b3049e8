// The [trace] keys: how many rays, how many orders are kept apart, the bounce cap, the batches
// that give every standard error, and the accuracy target (accuracy_target.cpp).
#include "gonio/trace/gonioreflectometer.h"

namespace gonio {

namespace {
const Key kRays = Key::integer("rays", {1, 1e12},
                               "rays per incidence, rounded up to B·S²: B independent stratified "
                               "S × S beams (with a target: one round)")
                      .fallback(double(1 << 20));
const Key kBatches = Key::integer("batches", {2, 1024},
                                  "B, the independent batches whose spread gives every standard "
                                  "error")
                         .fallback(32.0);
const Key kOrders =
    Key::integer("orders", {1, 1000}, "bounce orders stored separately, then one overflow order")
        .fallback(10.0);
const Key kMaxBounces = Key::integer("max_bounces", {1, 1e6},
                                     "rays still bouncing are cut (ledger: capped); 1 traces L1 "
                                     "only")
                            .fallback(1000.0);
// The backends' names and summaries from their registry (trace_backend.h).
const Key& backend_key() {
    static const Key key = [] {
        std::vector<std::string> names;
        std::string meaning = "what traces the rays (the same triangles and hits either way):";
        for (const TraceBackendKind* b : trace_backends()) {
            names.push_back(b->name);
            meaning +=
                std::string(names.size() > 1 ? ";" : "") + " `" + b->name + "`, " + b->summary;
        }
        return Key::string("backend", names, meaning).fallback(default_trace_backend().name);
    }();
    return key;
}
} // namespace

TraceSettings read_trace(TableReader& r) {
    TraceSettings s;
    s.rays = r.integer(kRays);
    s.orders = static_cast<int>(r.integer(kOrders));
    s.max_bounces = static_cast<int>(r.integer(kMaxBounces));
    s.batches = static_cast<int>(r.integer(kBatches));
    s.target = read_accuracy_target(r, s.rays);
    s.backend = &trace_backend_named(r.string(backend_key()));
    return s;
}

std::vector<KeyGroup> trace_key_groups() {
    std::vector<Key> keys{kRays, kBatches, kOrders, kMaxBounces, backend_key()};
    for (const Key& k : accuracy_target_keys()) keys.push_back(k);
    return {{"trace", "", "", keys}};
}

} // namespace gonio
