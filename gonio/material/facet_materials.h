#pragma once
// What a case's facets do, as the parts traced separately: one material, except a dispersive
// dielectric, whose channels refract apart and are traced one by one.
#include "gonio/config/config.h"
#include "gonio/material/material.h"

#include <memory>
#include <vector>

namespace gonio {

std::vector<std::unique_ptr<Material>> facet_materials(const CaseConfig& c);

} // namespace gonio
