#pragma once
// The integral of a density over every cell of a Beckers sensor (expected counts of a chi-square
// test, target masses of a distribution): 8 x 8 Gauss-Legendre points on each quarter of a cell,
// in (cos theta, phi) where dw = d(cos theta) dphi. The cells are integrated in parallel: the
// density must be safe to call from several threads.
#include "sensor/beckers_sensor.h"

#include <functional>
#include <vector>

namespace gonio {

std::vector<double> integrate_over_cells(const BeckersSensor& sensor,
                                         const std::function<double(const Vec3&)>& density);

} // namespace gonio
