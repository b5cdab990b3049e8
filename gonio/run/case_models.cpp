#include "gonio/run/case_models.h"

#include "core/check.h"

namespace gonio {

CaseModels::CaseModels(const CaseConfig& c, const HeightField* surface) {
    for (const ModelChoice& choice : c.model.models) {
        GONIO_CHECK_MSG(surface || !choice.needs_surface,
                        "model " + choice.name + " is fitted to the case's surface");
        models_.push_back(choice.build(surface));
    }
}

std::vector<ModelIncidence> CaseModels::evaluate(const Vec3& wi, const BeckersSensor& sensor,
                                                 std::uint64_t seed, std::uint64_t stream,
                                                 int surfaces) const {
    GONIO_CHECK(surfaces >= 1 && surfaces <= surfaces_);
    std::vector<ModelIncidence> out;
    out.reserve(models_.size());
    for (const auto& m : models_) out.push_back(m->evaluate_on(wi, sensor, seed, stream, surfaces));
    return out;
}

void CaseModels::add_surface(const HeightField& surface) {
    for (const auto& m : models_) m->add_surface(surface);
    ++surfaces_;
}

} // namespace gonio
