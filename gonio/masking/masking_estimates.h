#pragma once
// From the counts of gonio masking (masking_measurement.h) to what it reports: the measured G1 and
// G2 with their standard errors, the weak white furnace, and beside them Smith's forms built from
// the analytic NDF and from the surface's own facet NDF D_s (its Lambda from the back-facing
// projected area of D_s). Standard errors are binomial for one surface; for an ensemble they are
// the spread of the surfaces' own estimates (batch means over surfaces), so that they include the
// surface's spread — but for the weak furnace, exact on every surface, whose error is its points'.
// An ensemble's Smith (D_s) forms use the first surface's D_s; its height quantiles are each
// surface's own, and the edges written are the first surface's.
#include "core/named_array.h"
#include "gonio/masking/masking_measurement.h"
#include "heightfield/ndf/ndf.h"

#include <map>
#include <string>
#include <vector>

namespace gonio {

struct MaskingEstimates {
    // Axes.
    std::vector<double> theta_o, phi_o, g2_theta_o, g2_dphi, theta_i, phi_i;
    std::vector<double> bin_theta, bin_phi; // normal bins' centres (degrees)
    std::vector<double> height_edges;
    // Named arrays, in the order they are written.
    std::vector<std::pair<std::string, Array>> arrays;
    int surfaces = 0;
    long long points = 0;

    const Array& operator[](const std::string& name) const;
};

// `per_surface`: one count per surface of the case (one for a single surface).
MaskingEstimates estimate_masking(const std::vector<MaskingCounts>& per_surface,
                                  const MaskingGrid& grid, const Ndf& target, const Ndf& facet_ndf);

} // namespace gonio
