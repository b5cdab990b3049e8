#pragma once
// A gonio run as described by a TOML file: the cases, each with its distribution (built), its
// facets, incidence sweep, sensor, models, trace and surface settings. Every component reads its
// own keys (the registries: heightfield/ndf/ndf_family.h, gonio/material/material_kind.h,
// gonio/model/model_kind.h, heightfield/surface_spec.h, gonio/trace/gonioreflectometer.h);
// load_config validates everything before any work starts. `gonio keys` and the
// table of docs/configuration.md are generated from the same declarations.
#include "gonio/material/material_kind.h"
#include "gonio/model/model_kind.h"
#include "gonio/trace/gonioreflectometer.h"
#include "heightfield/ndf/ndf.h"
#include "heightfield/surface_spec.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gonio {

struct CaseConfig {
    std::string name;
    std::shared_ptr<const Ndf> ndf;  // [ndf], built
    double ndf_seconds = 0;          // the time it took (tables included)
    FacetSpec material;              // [material] (and [spectrum])
    std::vector<double> theta_i_deg; // [beam]: each in [0, 90); empty when not given
    std::vector<double> phi_i_deg;   // each in [0, 360]
    int sensor_cells = 3240;         // [sensor]
    ModelSettings model;             // [model]
    TraceSettings trace;             // [trace] (seed and stream are set per incidence)
    SurfaceSpec surface;             // [surface]

    int channels() const { return material.channels; }
    // A model is fitted to the traced surface (the P-BRDF): it must be made even by `gonio model`.
    bool needs_surface() const;
};

struct Config {
    std::string path;                   // the config file as given
    std::string text;                   // its text, as read
    std::vector<std::string> overrides; // --set assignments, in order
    std::string effective_toml;         // the document after overrides, re-serialised
    std::uint64_t seed = 1;
    std::vector<CaseConfig> cases;

    // Throws ConfigError (naming beam.theta_i) unless every case has an incidence sweep:
    // `command` is what needs it ("gonio run").
    void require_beam(const std::string& command) const;
};

// Reads, applies `overrides` ("key.path=value"), validates. Throws ConfigError.
Config load_config(const std::string& path, const std::vector<std::string>& overrides = {});
// The same from a string (tests); `path` is only used in messages.
Config parse_config(const std::string& text, const std::string& path,
                    const std::vector<std::string>& overrides = {});

// Every key of every section and component: for `gonio keys`, the table of docs/configuration.md and the checks.
std::vector<KeyGroup> config_key_groups();
// The keys as a Markdown table (docs/configuration.md) and as plain text.
std::string keys_markdown();
std::string keys_text();

} // namespace gonio
