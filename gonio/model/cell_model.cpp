#include "gonio/model/cell_model.h"

#include "core/batch_means.h"
#include "core/check.h"
#include "gonio/trace/trace_result.h"

#include <chrono>

namespace gonio {

ModelIncidence IntegratedModel::evaluate(const Vec3& wi, const BeckersSensor& sensor, std::uint64_t,
                                         std::uint64_t) const {
    const auto start = std::chrono::steady_clock::now();
    ModelIncidence m;
    m.energy = model_cell_energy(*model_, wi, sensor, quadrature_, &m.relative_tolerance);
    m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return m;
}

ModelIncidence monte_carlo_incidence(const TraceResult& v) {
    const int no = v.orders, B = v.batches;
    GONIO_CHECK(no == ModelIncidence::kOrderBins);
    auto orders = [&](const std::vector<double>& x, int from, int to) {
        return sum_orders(x, 1, no, from, to); // of the means: one "batch"
    };
    ModelIncidence m;
    m.energy = orders(v.energy, 0, no);
    m.l1_energy = orders(v.energy, 0, 1);
    m.l1_albedo = orders(v.ledger.reflected, 0, 1);
    m.l2_albedo = orders(v.ledger.reflected, 1, 2);
    m.l2plus_albedo = orders(v.ledger.reflected, 1, no);
    m.batches = B;
    m.energy_batches = v.sum_batches(0, no);
    m.l1_energy_batches = v.sum_batches(0, 1);
    m.albedo_stderr = batch_stderr(sum_orders(v.ledger_batches.reflected, B, no, 0, no), B);
    m.order_albedo = v.ledger.reflected;
    m.order_albedo_stderr = v.ledger_stderr.reflected;
    m.order_transmittance = v.ledger.transmitted;
    m.order_transmittance_stderr = v.ledger_stderr.transmitted;
    return m;
}

} // namespace gonio
