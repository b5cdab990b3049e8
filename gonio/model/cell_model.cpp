#include "gonio/model/cell_model.h"

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

} // namespace gonio
