#pragma once
// Builds a distribution from its validated description (the config's [ndf] table).
#include "heightfield/ndf/ndf.h"

#include <memory>
#include <string>
#include <vector>

namespace gonio {

struct NdfSpec {
    // "beckmann" | "ggx" | "student_t" | "generalized_normal" | "generalized_t" | "gaussian" |
    // "piecewise_linear" | "sinc" | "blend" | "mixture" | "tabulated" | "height_map"
    std::string type = "beckmann";
    double alpha_x = 0.5;
    double alpha_y = 0.5;
    double gamma = 2;                    // student_t
    double p = 2;                        // generalized_normal, generalized_t
    double q = 1;                        // generalized_t
    double sigma = 0.2;                  // gaussian, radians
    double theta_max = 89.9 * kPi / 180; // gaussian: where it is cut, radians
    double k = 6;                        // sinc, per radian
    double floor = 0;                    // sinc, relative to the peak
    int intervals = 128; // sinc, and piecewise_linear sampled from a source: points - 1
    std::vector<double> theta, value; // piecewise_linear control points (theta in radians)
    // blend: {along x, along y}; mixture: the components; piecewise_linear: {source} or none.
    std::vector<NdfSpec> parts;
    std::vector<double> weights; // mixture
    std::string file;            // tabulated (text or HDF5 table), height_map (EXR)
    int theta_intervals = 45;    // height_map: the facet table's grid (2 degrees)
    int phi_count = 36;          // (10 degrees)
};

// Throws std::invalid_argument (or std::runtime_error for an unreadable file) on bad parameters.
std::unique_ptr<Ndf> make_ndf(const NdfSpec& spec);

} // namespace gonio
