#pragma once
// What defines a generated surface (the config's [surface] table). Everything here, with the NDF,
// goes into the cache key.
#include <cstdint>
#include <string>

namespace gonio {

struct SurfaceSpec {
    // "sliced-matching" (default: see README), "algorithm1" (R19 Algorithm 1 as published) or
    // "heitz" (a periodic random-phase Gaussian surface: Beckmann slopes, Heitz 2015).
    std::string generator = "sliced-matching";
    // Constrained generation [R19 5.3.2]: the gradient field starts from a square lattice of
    // "domes" or "holes" instead of a random assignment ("none"); the pool still follows the NDF.
    std::string constraint = "none";
    double correlation_length = 8.0;  // heitz: Gaussian correlation length, in samples
    int size = 256;                   // samples per side
    double spacing = 1.0;             // distance between samples
    int iterations = 500;             // R19: 500
    double threshold = 0.02;          // Schwarz threshold, R19: 0.02
    bool stop_when_converged = false; // stop when the NDF distance stops improving
    std::uint64_t seed = 1;
    int lattice = 8;     // domes/holes: features per side
    double relief = 0.5; // domes/holes: feature height over its radius
    std::string input;   // an EXR height map to load instead of generating
    std::string edges =
        "periodic"; // loaded maps: "periodic" or "mirror" (made periodic by mirroring)
};

} // namespace gonio
