#pragma once
// Model L1 on the sensor cells, as cell averages (docs/models.md): the
// energy a model sends into cell c is E_c = integral over the cell of f(i, o) cos(theta_o) dw_o,
// and the cell's BRDF is E_c / Omega_c^perp with Omega_c^perp the cell's projected solid angle.
// Comparing cell averages with cell-centre values would be wrong for lobes narrower than a cell.
//
// Each cell is a rectangle in (cos theta, phi), where dw = d(cos theta) dphi. It is integrated by
// tensor Gauss-Legendre rules, split in two along its longer side while the split changes the
// result by more than the tolerance, and always split while it is wider than the distribution's
// narrowest feature and near the specular direction, so that no rule can step over a lobe narrower
// than a cell.
#include "gonio/model/brdf_model.h"
#include "sensor/beckers_sensor.h"

#include <vector>

namespace gonio {

struct CellQuadrature {
    int points = 4;        // Gauss-Legendre points per axis of each rectangle, in [1, 64]
    double rel_tol = 1e-6; // relative tolerance on each cell's energy
    int max_depth = 48;    // largest number of successive halvings of a cell
    long max_pieces = 1L << 18; // most splits of one cell (bounds the work of any integrand)
};

// E[c * channels + k]: energy fraction into cell c for channel k, incidence wi (unit, wi.z > 0).
// `reached`, when given, receives the relative error bound achieved: q.rel_tol, or more where a
// cell ran out of pieces first.
std::vector<double> model_cell_energy(const BrdfModel& model, const Vec3& wi,
                                      const BeckersSensor& sensor, const CellQuadrature& q,
                                      double* reached = nullptr);

// Directional albedo per channel: the sum of the cells' energies.
std::vector<double> albedo_from_cells(const std::vector<double>& energy, int channels);

} // namespace gonio
