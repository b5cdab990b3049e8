#pragma once
// A distribution tabulated on a (theta, phi) grid: measured data (a text or HDF5 file) or the facet
// normals of a height map. TabulatedNdf interpolates it bilinearly and normalises it.
//
// Grid: theta_j = j (pi/2) / theta_intervals, j = 0 .. theta_intervals (both ends included);
// phi_k = k 2 pi / phi_count, k = 0 .. phi_count - 1 (periodic). One column is an isotropic table.
#include "heightfield/heightfield.h"
#include "heightfield/ndf/ndf.h"

#include <string>
#include <vector>

namespace gonio {

struct NdfTable {
    int theta_intervals = 0;
    int phi_count = 0;
    std::vector<double> values; // row-major: values[j * phi_count + k], any positive scale
    double at(int j, int k) const { return values[size_t(j) * phi_count + k]; }
};

// Reads a table. Text: rows of numbers (spaces or commas; '#' starts a comment), one row per theta
// from 0 to 90 degrees, one column per phi from 0 (360 excluded). HDF5 (.h5, .hdf5): a 2-D double
// dataset "D" of the same layout. Throws std::runtime_error naming the file and the problem.
NdfTable read_ndf_table(const std::string& path);

// A distribution's D sampled on the grid (the horizon row just above it): a table of any NDF.
NdfTable sample_ndf_table(const Ndf& ndf, int theta_intervals, int phi_count);

// The facet distribution of a height map's triangles, each weighted by its projected area (the
// density D(m) cos theta_m), by cloud-in-cell deposit on the grid's nodes divided by each node's
// hat-function measure: D up to the normalisation.
NdfTable facet_ndf_table(const HeightField& surface, int theta_intervals, int phi_count);
// The same from normals drawn with density D(m) cos theta_m.
NdfTable ndf_table_of_normals(const std::vector<Vec3>& normals, int theta_intervals, int phi_count);

} // namespace gonio
