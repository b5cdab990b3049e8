#pragma once
// A periodic Gaussian random surface with Beckmann-distributed slopes, for comparison with the
// generated ones (R19 Fig. 9 compares against Heitz 2015, "Generating Procedural Beckmann
// Surfaces"). Heitz sums random-phase cosines with Gaussian-distributed frequencies; here the
// frequencies are those of the patch's lattice (random-phase FFT synthesis with a Gaussian power
// spectrum), so the surface is periodic. Slopes of a Gaussian field are Gaussian: the field is
// scaled so that the RMS forward-difference slope along x is alpha_x / sqrt(2), and the spectrum is
// stretched by alpha so that y follows alpha_y.
#include "heightfield/heightfield.h"

#include <cstdint>

namespace gonio {

// n samples per side (grid units: spacing 1), correlation length in samples (> 0).
HeightField heitz_surface(int n, double alpha_x, double alpha_y, double correlation_length,
                          std::uint64_t seed);

} // namespace gonio
