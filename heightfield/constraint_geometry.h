#pragma once
// Geometries that constrained generation starts from [R19 5.3.2, Fig. 15]: a square lattice of
// domes or of holes over the periodic patch.
#include "heightfield/heightfield.h"
#include "heightfield/surface_spec.h"

#include <string>

namespace gonio {

// n samples per side (grid units), `lattice` features per side, each a paraboloid cap of radius
// 0.4 of the lattice period and height relief * radius (negative for holes).
HeightField constraint_geometry(Constraint kind, int n, int lattice, double relief);

} // namespace gonio
