#pragma once
// CIEDE2000 difference images between two renders (R19 section 5 compares renderings so: Fig. 1,
// 12, 13) and their false-colour picture with a colour bar.
#include "gonio/render/image.h"

#include <cstdint>
#include <vector>

namespace gonio {

// Per pixel: Delta E00 of the two images' displayed colours (linear sRGB clipped to [0, 1], then
// CIE L*a*b* against D65).
std::vector<double> delta_e00(const Image& a, const Image& b);

struct DifferenceStats {
    double mean = 0, p95 = 0, max = 0;
    long long pixels = 0;
};
// Over the pixels where mask != 0 (the object).
DifferenceStats difference_stats(const std::vector<double>& de,
                                 const std::vector<std::uint8_t>& mask);

// The false-colour picture: blue (0) through cyan, green and yellow to red (at `scale`, and
// above), with a colour bar below the image marked at 0, 1, 3 (R19's range of perceptibility), 5
// and 10.
constexpr double kDeltaEScale = 10.0;
Image false_colour(const std::vector<double>& de, int width, int height,
                   double scale = kDeltaEScale);
std::array<float, 3> false_colour_of(double value, double scale = kDeltaEScale);

} // namespace gonio
