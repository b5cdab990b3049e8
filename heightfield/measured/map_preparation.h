#pragma once
// What a measured map needs before it can be traced as a periodic patch: spikes removed (a robust
// local rule), missing points filled, the tilt or form levelled, optionally the waviness removed
// by a Gaussian high-pass, and a square cut out of a rectangular map. Each step is a surface key
// (surface_spec.cpp) and says what it did.
#include "core/enum_names.h"
#include "heightfield/heightfield.h"
#include "heightfield/measured/measured_map.h"

#include <string>
#include <vector>

namespace gonio {

// Least-squares polynomial form removed: none, a plane, or a surface of degree 2 or 3.
enum class Levelling { none, plane, quadratic, cubic };
template <>
struct EnumNames<Levelling> {
    static constexpr const char* what = "levelling";
    static constexpr const char* names[] = {"none", "plane", "quadratic", "cubic"};
};

struct MapPreparation {
    Levelling level = Levelling::plane;
    double max_missing = 0.05; // the largest share of missing points (spikes included) filled
    double spikes = 20;        // robust sigmas of the local residual beyond which a point is a
                               // spike (0: none removed)
    double high_pass = 0;      // the Gaussian high-pass's cut-off wavelength, in the map's length
                               // unit (0: none; gaussian_filter.h)
};

struct PreparedMap {
    HeightField surface;
    double missing_share = 0;        // points the file marks missing
    double spike_share = 0;          // points removed as spikes
    std::vector<std::string> report; // one line per step, for gonio surface and the result
};

// Throws std::runtime_error naming `path` and the key when the map cannot be prepared (too many
// missing points, non-square cells).
PreparedMap prepare_measured_map(const MeasuredMap& map, const MapPreparation& p,
                                 const std::string& path);

} // namespace gonio
