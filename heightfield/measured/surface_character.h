#pragma once
// What a measured surface is, in the terms of the analytic models: its RMS slopes along its
// principal axes and their direction (the anisotropy), and the isotropic GGX and Beckmann
// distributions closest to its facet normals (the roughness minimising the total-variation
// distance of surface_metrics.h).
#include "heightfield/heightfield.h"

#include <string>

namespace gonio {

struct AnalyticFit {
    std::string family; // ggx, beckmann
    double alpha = 0;
    double distance = 0; // total-variation distance of the facet normals to D(m) cos(theta_m)
};

struct SurfaceCharacter {
    // sqrt(2) x RMS slope along the slopes' principal axes (Beckmann's alpha definition), the
    // larger first, and the azimuth of the first axis in degrees [0, 180).
    double alpha_major = 0, alpha_minor = 0, major_axis_deg = 0;
    AnalyticFit ggx, beckmann;
    const AnalyticFit& best() const { return ggx.distance <= beckmann.distance ? ggx : beckmann; }
};

// `bins`: the equal-area cells of the distance (surface_metrics.h's default).
SurfaceCharacter characterise_surface(const HeightField& surface, int bins = 1000);

} // namespace gonio
