#pragma once
// What defines a generated surface (the config's [surface] table). Everything here, with the NDF,
// goes into the cache key.
#include <cstdint>
#include <string>

namespace gonio {

struct SurfaceSpec {
    // "sliced-matching" (default: see README) or "algorithm1" (R19 Algorithm 1 as published).
    std::string generator = "sliced-matching";
    int size = 256;               // samples per side
    double spacing = 1.0;         // distance between samples
    int iterations = 500;         // R19: 500
    double threshold = 0.02;      // Schwarz threshold, R19: 0.02
    bool stop_when_converged = false; // stop when the NDF distance stops improving
    std::uint64_t seed = 1;
    int lattice = 8;              // domes/holes: features per side
    double relief = 0.3;          // domes/holes: feature height over its radius
    std::string input;            // an EXR height map to load instead of generating
    std::string edges = "periodic"; // loaded maps: "periodic" or "mirror" (made periodic by mirroring)
};

} // namespace gonio
