#pragma once
// Where a case's microsurface comes from: the cache, the generator, or a measured height map.
// gonio surface and (later) gonio run both go through here, so a sweep never regenerates.
#include "heightfield/generate.h"
#include "heightfield/surface_cache.h"

#include <string>
#include <vector>

namespace gonio {

struct SurfaceOrigin {
    bool from_cache = false;
    bool generated = false;
    bool loaded = false;                  // from surface.input
    std::string cache_path;               // where it is (or was stored) in the cache, if enabled
    std::string edges;                    // loaded maps: how the edges were handled
    std::string warning;                  // e.g. a non-periodic measured map
    std::vector<std::string> preparation; // loaded maps: what was read and done to them
    GenerationLog log;                    // when generated, or as stored with a cached surface
};

// Gets the surface of (ndf, spec), through `cache` when enabled.
HeightField obtain_surface(const Ndf& ndf, const SurfaceSpec& spec, const SurfaceCache& cache,
                           int threads, SurfaceOrigin& origin, const ProgressFn& progress = {});

// The measured map of spec.input (any format of measured/measured_map.h), prepared as the
// surface keys ask (measured/map_preparation.h), with a line per step in `report`. OpenEXR maps
// are read exactly as stored unless a preparation key is given. Throws std::runtime_error naming
// the file.
HeightField read_input_map(const SurfaceSpec& spec, std::vector<std::string>& report);

// Seam discontinuity of a height map over its interior step: ~1 for periodic maps.
double seam_ratio(const HeightField& s);
// A periodic 2n x 2n map made of s and its mirror images.
HeightField mirror_tile(const HeightField& s);

// EXR attributes describing a surface (identity, generator, seed, iterations, Schwarz log).
ExrAttributes surface_attributes(const Ndf& ndf, const SurfaceSpec& spec, const GenerationLog& log);

} // namespace gonio
