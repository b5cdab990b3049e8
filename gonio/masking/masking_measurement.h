#pragma once
// The masking and shadowing of an explicit surface, measured by ray casting (gonio masking).
//
// Points are drawn uniformly by area on the triangulated facets (so a facet normal m is drawn with
// the surface's own facet NDF D_s(m) dm); from each, rays towards a grid of directions w say
// whether the point sees w (the periodic traversal, exact wrap). Over the points:
//   - G1(w, m): the fraction of points on front-facing facets in a normal bin that see w;
//   - G1(w, height quantile): the same by the point's height;
//   - the weak white furnace: (A_micro / A_macro) E[V(w) <w, m>+] = cos theta_w exactly on a height
//     field (the visible projected area is the macro area's), a self-test at every w [Heitz 2014
//     section 3, JCGT 3(2)]; it is also the projected-area average of G1, Smith's 1 / (1 +
//     Lambda_s);
//   - G2(wi, wo, m): the fraction of points facing both that see both, at the config's incidences
//     and a grid of wo around each (retro-reflection, wo = wi, included).
// Counts are integers (exact in any order); the one floating sum, the furnace's, is made per
// fixed block of points and added in block order, so results do not depend on the threads.
#include "gonio/trace/scene.h"
#include "heightfield/heightfield.h"
#include "sensor/beckers_sensor.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace gonio {

struct MaskingGrid {
    std::vector<double> theta_o_deg; // G1 and the furnace: polar angles of w
    std::vector<double> phi_o_deg;   // and their azimuths (one suffices for isotropic surfaces)
    int normal_bins = 145;           // equal-area (Beckers) bins of the facet normal
    int height_bins = 8;             // quantiles of the points' heights
    std::vector<double> theta_i_deg, phi_i_deg; // G2's incidences (every pair)
    std::vector<double> g2_theta_o_deg;         // G2's wo: polar angles (wi's own added)
    std::vector<double> g2_dphi_deg;            // and azimuths relative to phi_i (0: retro side)
};

// Counts over the points of one surface (or, added, of an ensemble).
struct MaskingCounts {
    long long points = 0;
    double area_ratio = 0; // A_micro / A_macro of the surface
    // [w][normal bin] and [w][height bin]: points on facets facing w, and of them those that see w.
    std::vector<long long> g1_front, g1_visible, g1h_front, g1h_visible;
    // [w]: sum and sum of squares of (A_micro / A_macro) V(w) <w, m>+ over the points, and the
    // sum of (A_micro / A_macro) <w, m>+ (visible or not): their ratio is the projected-area G1.
    std::vector<double> furnace_sum, furnace_sum2, projected_sum, projected_sum2;
    // [incidence][wo][normal bin]: points facing wi and wo, and of them those that see both.
    std::vector<long long> g2_front, g2_visible;
    std::vector<double> height_edges; // the quantiles' edges (height_bins + 1)

    void add(const MaskingCounts& other); // an ensemble's counts (heights edges: the first's)
};

// The directions of the grid, in order: G1's w (theta major), G2's wo for each incidence.
struct MaskingDirections {
    std::vector<Vec3> w;               // G1
    std::vector<double> g2_theta_deg;  // G2's polar angles (grid and the incidences' own)
    std::vector<Vec3> wi;              // incidences, theta_i major
    std::vector<std::vector<Vec3>> wo; // per incidence: [theta][dphi]
};
MaskingDirections masking_directions(const MaskingGrid& grid);

using MaskingProgress = std::function<void(double fraction)>;

// Measures one surface on `points` points, G2 on the first `g2_points` of them (G2 needs a ray per
// incidence and direction of its grid from every point). `seed` keys the points.
MaskingCounts measure_masking(const HeightField& surface, const Scene& scene,
                              const MaskingGrid& grid, long long points, long long g2_points,
                              std::uint64_t seed, const MaskingProgress& progress = {});

} // namespace gonio
