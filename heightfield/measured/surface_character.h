#pragma once
// What a measured surface is, in the terms of the analytic models: its RMS slopes along its
// principal axes and their direction (the anisotropy), its correlation lengths, and the GGX and
// Beckmann distributions closest to its facet normals (minimising the total-variation distance
// of surface_metrics.h), isotropic and with one roughness along each of the grid's axes.
#include "heightfield/heightfield.h"

#include <string>
#include <vector>

namespace gonio {

struct AnalyticFit {
    std::string family;              // ggx, beckmann
    double alpha_x = 0, alpha_y = 0; // equal for an isotropic fit
    double distance = 0; // total-variation distance of the facet normals to D(m) cos(theta_m)
    // An alpha at the search's end: the least distance may lie beyond, where the metric's cells
    // cannot follow the family (below) or no family member is steeper (above).
    bool at_lowest = false, at_highest = false;
    // Within 0.1 %: printed as one alpha.
    bool isotropic() const;
    // The fit as a case's `ndf` table: { type = "ggx", alpha = 0.116 }.
    std::string ndf_toml() const;
};

struct SurfaceCharacter {
    // sqrt(2) x RMS slope along the slopes' principal axes (Beckmann's alpha definition), the
    // larger first, and the azimuth of the first axis in degrees [0, 180).
    double alpha_major = 0, alpha_minor = 0, major_axis_deg = 0;
    // The heights' autocorrelation lengths (1/e) along x and y, in the map's length unit; a
    // length that reaches half the map is only known to be at least that (`*_capped`).
    double correlation_x = 0, correlation_y = 0;
    bool correlation_x_capped = false, correlation_y_capped = false;
    // The roughness the metric's cells resolve: narrower distributions than this put all their
    // mass in the central cell, where its quadrature cannot follow them. A surface smoother than
    // that (99 % of its facets in the central cell) is `unresolved`: it has no fit.
    double lowest_alpha = 0;
    bool unresolved = false;
    AnalyticFit ggx, beckmann;       // isotropic
    AnalyticFit ggx_xy, beckmann_xy; // alpha_x and alpha_y along the grid's axes
    const AnalyticFit& best() const { return ggx.distance <= beckmann.distance ? ggx : beckmann; }
    const AnalyticFit& best_xy() const {
        return ggx_xy.distance <= beckmann_xy.distance ? ggx_xy : beckmann_xy;
    }
    // What gonio surface prints, one line each (it prints the correlation lengths with the
    // heights); summary() is the correlation lengths and these lines, for the result file.
    std::vector<std::string> lines() const;
    std::string summary() const;
};

// `bins`: the equal-area cells of the distance (surface_metrics.h's default).
SurfaceCharacter characterise_surface(const HeightField& surface, int bins = 1000);

} // namespace gonio
