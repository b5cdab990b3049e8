#pragma once
// The registry of facet materials ([material] type): each kind declares its keys and reads itself
// into a FacetSpec, everything the tracer and the models need of a case's facets. Config loading,
// `gonio keys` and the configuration table (docs/configuration.md) come from this list.
#include "core/config_key.h"
#include "core/table_reader.h"
#include "gonio/material/fresnel_term.h"
#include "gonio/material/material.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace gonio {

// The most channels (wavelengths) a material may have.
inline constexpr int kMaxChannels = 64;

struct FacetSpec {
    std::string type;        // the kind's name
    std::string description; // with its parameters, for files and listings
    std::string source;      // where the optical constants came from (a table path), or ""
    bool diffuse = false;    // Lambertian substrate (the IL model) rather than a specular facet
    bool transmits = false;  // rays may cross the surface (dielectrics)
    int channels = 1;
    std::vector<double> wavelengths_nm; // one per channel; empty when achromatic
    FresnelTerm fresnel;                // specular facets
    std::vector<double> albedo;         // diffuse facets: K_d per channel (or one)
    std::vector<double> interface_eta;  // diffuse facets: n_i per channel (1: no interface)
    // The parts traced separately: one material, except a dispersive dielectric, whose channels
    // refract apart and are traced one by one.
    std::function<std::vector<std::unique_ptr<Material>>()> parts;
};

struct MaterialKind {
    std::string name;
    std::string summary;
    std::vector<Key> keys;
    // Reads the kind's keys; `spectrum` is read only by spectral materials (so an unused
    // [spectrum] is reported).
    FacetSpec (*create)(TableReader& r, TableReader& spectrum);
};

const std::vector<const MaterialKind*>& material_kinds();
// Reads [material] type and that kind's keys.
FacetSpec read_material(TableReader r, TableReader spectrum);
// [material] and [spectrum] keys, for listings.
std::vector<KeyGroup> material_key_groups();

// Kinds' declarations.
const MaterialKind& mirror_kind();
const MaterialKind& conductor_kind();
const MaterialKind& dielectric_kind();
const MaterialKind& schlick_kind();
const MaterialKind& lambertian_kind();
const MaterialKind& interfaced_lambertian_kind();

// Shared by the spectral kinds: the channels' wavelengths, and a list that is one value
// (achromatic) or one per wavelength.
std::vector<double> read_wavelengths(TableReader& spectrum);
std::vector<double> read_per_channel(TableReader& r, const Key& key, TableReader& spectrum,
                                     std::vector<double>& wavelengths);
std::string list_text(const std::vector<double>& v); // "1.5" or "1.5, 1.6"

} // namespace gonio
