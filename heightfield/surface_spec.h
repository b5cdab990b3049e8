#pragma once
// What defines a generated surface (the config's [surface] table). Everything here, with the NDF,
// goes into the cache key. The generators' keys are declared in surface_spec.cpp, where the
// [surface] table is read.
#include "core/config_key.h"
#include "core/enum_names.h"
#include "core/table_reader.h"

#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

class Ndf;
struct SurfaceGenerator;                     // surface_generator.h: the generators' registry
const SurfaceGenerator* default_generator(); // sliced matching

// Constrained generation [R19 5.3.2]: the gradient field starts from a square lattice of domes
// or holes instead of a random assignment; the pool still follows the NDF.
enum class Constraint { none, domes, holes };
template <>
struct EnumNames<Constraint> {
    static constexpr const char* what = "constraint";
    static constexpr const char* names[] = {"none", "domes", "holes"};
};
// What sliced matching matches each direction's projections to: the exact marginal of the NDF
// (a quantile table computed from it, two orthogonal directions per iteration), or the marginal of
// the sample pool (one direction per iteration: the generator of gonio 0.x, for its surfaces).
enum class MatchTarget { quantiles, pool };
template <>
struct EnumNames<MatchTarget> {
    static constexpr const char* what = "target";
    static constexpr const char* names[] = {"quantiles", "pool"};
};
// Loaded maps: used as they are, or made periodic by tiling with mirror images.
enum class Edges { periodic, mirror };
template <>
struct EnumNames<Edges> {
    static constexpr const char* what = "edges";
    static constexpr const char* names[] = {"periodic", "mirror"};
};

struct SurfaceSpec {
    // How it is made; null for a measured map (input).
    const SurfaceGenerator* generator = default_generator();
    // The matching generators' settings (sliced-matching, algorithm1) and heitz's.
    Constraint constraint = Constraint::none;
    MatchTarget target = MatchTarget::quantiles; // sliced-matching: see MatchTarget
    double correlation_length = 8.0;             // heitz: Gaussian correlation length, in samples
    int size = 256;                              // samples per side
    double spacing = 1.0;                        // distance between samples
    int iterations = 100;             // sliced-matching of the quantiles; R19 (algorithm1): 500
    double threshold = 0.02;          // Schwarz threshold, R19: 0.02
    bool stop_when_converged = false; // stop when the NDF distance stops improving
    std::uint64_t seed = 1;
    int lattice = 8;               // domes/holes: features per side
    double relief = 0.5;           // domes/holes: feature height over its radius
    std::string input;             // an EXR height map to load instead of generating
    Edges edges = Edges::periodic; // loaded maps
    // A measured map's preparation (measured/map_preparation.h): `level` auto is a plane for
    // third-party formats and none for OpenEXR maps, `spikes` < 0 is 20 and 0 likewise; an
    // OpenEXR map is read exactly as stored unless one of these keys is given.
    std::string level = "auto";
    double spikes = -1;
    double max_missing = 0.05;
    double high_pass = 0;     // the Gaussian high-pass's cut-off wavelength (0: none)
    double input_spacing = 0; // plain matrices, in input_unit
    std::string input_unit = "um";
    bool input_checksums = true; // refuse files whose checksums fail
    bool prepare_asked = false;
    // An ensemble: independent surfaces of the same distribution (realisation r has the seed
    // realisation_seed(seed, r)), so that errors include the surfaces' spread.
    int realisations = 1;
    int max_realisations = 64; // with an accuracy target: how far it may grow the ensemble
};

// The generator's name, or "input" for a measured map.
const char* generator_name(const SurfaceSpec& spec);

// The seed of realisation r: `seed` itself for r = 0 (one surface is the surface of a run without
// an ensemble), a hash of (seed, r) otherwise, so that two seeds share no surface.
std::uint64_t realisation_seed(std::uint64_t seed, int r);
// The spec of realisation r (its seed; the ensemble keys do not define a surface).
SurfaceSpec realisation(const SurfaceSpec& spec, int r);

// Reads [surface] for a case whose distribution is `ndf`; `seed` is the run's seed (the default
// of surface.seed).
// `target`: the case has an accuracy target (surface.max_realisations applies only then).
SurfaceSpec read_surface(TableReader& r, std::uint64_t seed, const Ndf& ndf, bool target);
// The [surface] keys: common ones, then each generator's.
std::vector<KeyGroup> surface_key_groups();

} // namespace gonio
