#pragma once
// What a measured surface is, in the terms of the analytic models: its RMS slopes along its
// principal axes and their direction (the anisotropy), and the GGX and Beckmann distributions
// closest to its facet normals (minimising the total-variation distance of surface_metrics.h),
// isotropic and with one roughness along each of the grid's axes.
#include "heightfield/heightfield.h"

#include <string>

namespace gonio {

struct AnalyticFit {
    std::string family;              // ggx, beckmann
    double alpha_x = 0, alpha_y = 0; // equal for an isotropic fit
    double distance = 0; // total-variation distance of the facet normals to D(m) cos(theta_m)
    bool isotropic() const { return alpha_x == alpha_y; }
    // The fit as a case's `ndf` table: { type = "ggx", alpha = 0.116 }.
    std::string ndf_toml() const;
};

struct SurfaceCharacter {
    // sqrt(2) x RMS slope along the slopes' principal axes (Beckmann's alpha definition), the
    // larger first, and the azimuth of the first axis in degrees [0, 180).
    double alpha_major = 0, alpha_minor = 0, major_axis_deg = 0;
    // The heights' autocorrelation lengths along x and y (1/e), in the map's length unit.
    double correlation_x = 0, correlation_y = 0;
    AnalyticFit ggx, beckmann;       // isotropic
    AnalyticFit ggx_xy, beckmann_xy; // alpha_x and alpha_y along the grid's axes
    const AnalyticFit& best() const { return ggx.distance <= beckmann.distance ? ggx : beckmann; }
    const AnalyticFit& best_xy() const {
        return ggx_xy.distance <= beckmann_xy.distance ? ggx_xy : beckmann_xy;
    }
    // One line: the principal slopes and the fits, for gonio surface and the result file.
    std::string summary() const;
};

// `bins`: the equal-area cells of the distance (surface_metrics.h's default).
SurfaceCharacter characterise_surface(const HeightField& surface, int bins = 1000);

} // namespace gonio
