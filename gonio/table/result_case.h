#pragma once
// One case of a result file, as the tabulated BSDF and the exporters read it: its sweep, sensor,
// channels, which simulated orders it holds, and its config (re-read from the effective TOML the
// file stores, so that the NDF and the surface are known exactly).
#include "gonio/config/config.h"

#include <string>
#include <vector>

namespace gonio {

struct ResultCase {
    std::string file, name;
    CaseConfig config;
    std::string effective_toml;                                // the file's config_effective_toml
    std::string material;                                      // the case's `material` attribute
    std::vector<double> theta_i_deg, phi_i_deg, wavelength_nm; // as stored (sweep order)
    int cells = 0, channels = 1;
    bool simulated = false; // a `gonio run` case (brdf datasets), not `gonio model` only
    bool transmits = false; // has the lower sensor (btdf)
    bool isotropic = false; // case_is_isotropic(config)

    bool has(const std::string& dataset) const;
    // A per-cell map [theta_i][phi_i][cell][channel] or a per-incidence quantity
    // [theta_i][phi_i][channel] of the case's group, row-major, checked against the case's axes
    // and for values a BRDF, an albedo or an error can hold (finite, not negative); throws
    // std::runtime_error naming the file, the dataset and what is wrong.
    std::vector<double> read_map(const std::string& dataset) const;
    std::vector<double> read_albedo(const std::string& dataset) const;
};

// The case `name` of `file`, or its only case when `name` is empty. Throws std::runtime_error
// with the reason (no such file, not a result file, no such case: the list of cases).
ResultCase read_result_case(const std::string& file, const std::string& name);
// The names of the file's cases, in config order.
std::vector<std::string> read_result_case_names(const std::string& file);

// Whether the case's BSDF is invariant under rotations about the normal: an isotropic NDF
// (checked numerically on a grid of directions) on a generated, unconstrained surface (a loaded
// map or a lattice of domes or holes has directions of its own).
bool case_is_isotropic(const CaseConfig& c);

} // namespace gonio
