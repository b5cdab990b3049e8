#pragma once
// How faithfully a surface's facets follow a distribution, measured on the triangles rays see
// (heightfield.h), each weighted by its projected area (equal for all), i.e. against D(m)
// cos(theta_m).
#include "heightfield/heightfield.h"
#include "heightfield/ndf/ndf.h"

#include <vector>

namespace gonio {

struct SurfaceMetrics {
    // Total-variation distance 1/2 sum |measured - target| between the facet-normal distribution
    // and D(m) cos(theta_m), on `ndf_bins` equal-area Beckers cells of the hemisphere (0:
    // identical, 1: disjoint).
    double ndf_distance = 0;
    int ndf_bins = 0;
    std::vector<double> measured_mass, target_mass; // per Beckers cell
    // Effective roughness along x and y: alpha times the ratio of the median |slope| of the facets
    // to that of the target distribution (robust for heavy tails such as GGX, whose RMS slope is
    // infinite), and sqrt(2) times the RMS slope (Beckmann's alpha definition).
    double alpha_eff_x = 0, alpha_eff_y = 0;
    double alpha_rms_x = 0, alpha_rms_y = 0;
    double target_alpha_x = 0,
           target_alpha_y = 0; // 0 when the NDF has no stretch (not shape-invariant)
    // Heights: RMS, histogram (64 bins over [min, max]), autocorrelation length along x and y (the
    // lag where the autocorrelation falls to 1/e, in the units of the spacing; half the map when
    // it never does, 0 for a flat map).
    double height_rms = 0, height_min = 0, height_max = 0;
    std::vector<double> height_histogram;
    double correlation_length_x = 0, correlation_length_y = 0;
};

// The TV distance alone (cheap enough to monitor during generation).
double ndf_distance(const HeightField& surface, const Ndf& ndf, int bins);
SurfaceMetrics measure_surface(const HeightField& surface, const Ndf& ndf, int bins = 1000);

// Mass of D(m) cos(theta_m) in every cell of an equal-area sensor of `bins` cells.
std::vector<double> target_cell_mass(const Ndf& ndf, int bins);
// The share of the surface's facets (by projected area) whose normals fall in every cell.
std::vector<double> facet_cell_mass(const HeightField& surface, int bins);
// The heights' autocorrelation lengths along x and y (SurfaceMetrics').
void correlation_lengths(const HeightField& surface, double& along_x, double& along_y);
// 1/2 sum |a - b| over the cells.
double total_variation(const std::vector<double>& a, const std::vector<double>& b);

} // namespace gonio
