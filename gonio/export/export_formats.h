#pragma once
// What the formats of `gonio export` (export.h, one file each) share: which order a request means
// and the sweep that the whole-hemisphere formats (RGL, MERL) need.
#include "gonio/export/export.h"
#include "gonio/table/bsdf_table.h"
#include "gonio/table/result_case.h"

#include <ostream>

namespace gonio {

// The order of --orders; `t` is refused by formats of reflection.
TableOrder requested_order(const ExportOptions& o, bool transmission_allowed);
// Refuses sweeps a whole-hemisphere format cannot be filled from: theta_i must start within 1
// degree of the normal, reach 80 degrees, and have no gap wider than 10 degrees.
void require_hemisphere_sweep(const BsdfTable& t, const std::string& format);
// The table of the requested order, refusing a model-only file.
BsdfTable load_table(const ResultCase& c, TableOrder order, const std::string& format);

} // namespace gonio
