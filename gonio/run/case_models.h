#pragma once
// The models a case asks for ([model] models), built once per case (the P-BRDF is fitted to the
// case's first surface) and evaluated at each incidence, inside its work unit.
#include "gonio/config/config.h"
#include "gonio/model/cell_model.h"
#include "heightfield/heightfield.h"
#include "sensor/beckers_sensor.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace gonio {

class CaseModels {
  public:
    // `surface`: the case's first surface; needed only when c.needs_surface().
    CaseModels(const CaseConfig& c, const HeightField* surface);
    // Every model of the case at incidence wi, in the case's order; Monte Carlo models draw
    // from (seed, stream), the incidence's streams.
    std::vector<ModelIncidence> evaluate(const Vec3& wi, const BeckersSensor& sensor,
                                         std::uint64_t seed, std::uint64_t stream,
                                         int surfaces = 1) const;
    // Surface r >= 1 of an ensemble, in order, for the models of the surface itself.
    void add_surface(const HeightField& surface);
    int surfaces() const { return surfaces_; }

  private:
    std::vector<std::unique_ptr<CellModel>> models_;
    int surfaces_ = 1;
};

} // namespace gonio
