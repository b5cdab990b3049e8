#pragma once
// How a case's surface is made: each generator declares its name, its [surface] keys and their
// reading, what of its settings defines a surface (the cache key), and the generation itself.
// Each lives beside its code (generate.cpp: sliced-matching and algorithm1; heitz_surface.cpp:
// heitz) and is listed once in surface_generators(); `surface.generator`, `gonio keys` and the
// docs' key table take their names and keys from there.
#include "core/config_key.h"
#include "core/table_reader.h"
#include "heightfield/generate.h"
#include "heightfield/surface_spec.h"

#include <ostream>
#include <string>
#include <vector>

namespace gonio {

struct SurfaceGenerator {
    const char* name;
    const char* summary;
    const std::vector<Key>* keys; // its own keys in [surface] (generators may share one list)
    // Reads its keys into `spec`; refuses (r.fail on "generator") a distribution it cannot make.
    void (*read)(TableReader& r, const Ndf& ndf, SurfaceSpec& spec);
    // The surface in grid units (spacing 1; generate_surface scales the heights).
    HeightField (*generate)(const Ndf& ndf, const SurfaceSpec& spec, int threads,
                            GenerationLog* log, const ProgressFn& progress);
    // Its settings that define a surface, appended to the cache identity ("|key=value"...).
    void (*identity)(const SurfaceSpec& spec, std::ostream& out);
    // Its facets follow the NDF statistically (a constraint geometry makes them follow a shape).
    bool (*follows_ndf)(const SurfaceSpec& spec);
};

const std::vector<const SurfaceGenerator*>& surface_generators();
// Throws std::invalid_argument naming the generators.
const SurfaceGenerator& generator_named(const std::string& name);
const SurfaceGenerator& sliced_matching_generator();
const SurfaceGenerator& algorithm1_generator();
const SurfaceGenerator& heitz_generator();

} // namespace gonio
