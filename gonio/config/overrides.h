#pragma once
// Command-line overrides: "--set key.path=value" edits the parsed TOML document before validation.
// The path's segments are table keys; inside the array of cases a segment is a case's index
// (from 0) or its name: "case.1.ndf.alpha=0.3", "case.ggx.beam.theta_i=[0, 60]". The value is
// TOML ("0.3", "[0, 60]", "\"ggx\"") or, if it does not parse as TOML, a bare string ("ggx").
#include <string>
#include <toml++/toml.h>

namespace gonio {

// Throws ConfigError naming the assignment when it cannot be applied.
void apply_override(toml::table& root, const std::string& assignment, const std::string& file);

} // namespace gonio
