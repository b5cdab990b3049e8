#pragma once
// The areal Gaussian filter of surface metrology (ISO 16610-61): the long-wavelength part of a
// map, the form and waviness, removed by a cut-off wavelength, leaving the roughness. Its
// transmission is 50 % at the cut-off wavelength.
#include <vector>

namespace gonio {

// The Gaussian filter's transmission at spatial frequency f (1 / length) for cut-off wavelength
// `cutoff` (same length unit): exp(-pi (alpha cutoff f)^2), alpha = sqrt(ln 2 / pi)
// [ISO16610: ISO 16610-21 Sec. 4.2.1; ISO 16610-61's areal filter is its product along x, y].
double gaussian_transmission(double frequency, double cutoff);

// z (nx x ny, row-major, spacing `spacing`) minus its Gaussian low-pass of cut-off `cutoff`. The
// map is extended by its mirror images (an even, periodic extension, so that its edges do not
// jump), i.e. filtered in the basis of the discrete cosine transform (FFTW's REDFT10/REDFT01).
void gaussian_high_pass(std::vector<double>& z, int nx, int ny, double spacing, double cutoff);

} // namespace gonio
