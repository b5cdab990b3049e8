#pragma once
// The registry of distributions: each family declares, in its own file, its config keys and how
// it builds itself from a reader of its table (pbrt-v4's Create(ParameterDictionary), Mitsuba's
// plugin constructors). Config loading, `gonio keys` and the configuration table (docs/configuration.md) all read this list.
// A new family touches its own files, one line of ndf_families() and the CMake source list.
#include "core/config_key.h"
#include "core/table_reader.h"
#include "heightfield/ndf/ndf.h"

#include <memory>
#include <string>
#include <vector>

namespace gonio {

struct NdfFamily {
    std::string name;    // the value of ndf.type
    std::string summary; // one line, with the paper
    std::vector<Key> keys;
    // Reads the family's keys from `r` and builds the distribution; nested distributions are read
    // with read_ndf(table, depth + 1). Errors are reported through r.fail (file, line, key).
    std::unique_ptr<Ndf> (*create)(TableReader& r, int depth);
    // An isotropic curve when given one roughness: may be an axis of a blend [R19 Eq. 10].
    bool curve = false;
};

// Every family, in the order of docs/configuration.md.
const std::vector<const NdfFamily*>& ndf_families();
// The `type` key, whose choices are the families.
const Key& ndf_type_key();

// Reads `type` and builds that family's distribution. `family`, if given, receives it.
std::unique_ptr<Ndf> read_ndf(TableReader r, int depth = 0, const NdfFamily** family = nullptr);
// A distribution from the text of a TOML table ("type = \"ggx\"\nalpha = 0.3"): for tests and
// tools. Throws ConfigError like a config.
std::unique_ptr<Ndf> ndf_from_toml(const std::string& table_text);

// The families' keys, for listings.
std::vector<KeyGroup> ndf_key_groups();

// Families' declarations (each defined beside its distribution).
const NdfFamily& beckmann_family();
const NdfFamily& ggx_family();
const NdfFamily& student_t_family();
const NdfFamily& generalized_normal_family();
const NdfFamily& generalized_t_family();
const NdfFamily& gaussian_family();
const NdfFamily& piecewise_linear_family();
const NdfFamily& sinc_family();
const NdfFamily& blend_family();
const NdfFamily& mixture_family();
const NdfFamily& tabulated_family();
const NdfFamily& height_map_family();

// The roughness keys the alpha families share: alpha, or alpha_x and alpha_y (a case that gives
// any of them replaces the defaults' ones).
const std::vector<Key>& roughness_keys();
struct Roughness {
    double x, y;
};
Roughness read_roughness(TableReader& r);

} // namespace gonio
