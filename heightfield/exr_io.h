#pragma once
// Height maps as single-channel float OpenEXR images ("Y"), with gonio's metadata as header
// attributes (gonio_spacing, gonio_ndf, gonio_seed, gonio_iterations, gonio_generator, ...).
#include "heightfield/heightfield.h"

#include <map>
#include <string>
#include <vector>

namespace gonio {

struct ExrAttributes {
    std::map<std::string, std::string> text; // stored as string attributes
    std::map<std::string, double> numbers;   // stored as double attributes
};

// Writes `surface` to `path` (via a temporary file renamed when complete). Throws
// std::runtime_error naming the file on failure.
void write_height_exr(const std::string& path, const HeightField& surface,
                      const ExrAttributes& attrs);

// Reads a single-channel square height map (channel Y, Z, H or R), or a normal map (channels R, G,
// B holding the unit normal, no Y/Z/H) integrated into heights by Frankot-Chellappa (spacing 1).
// The spacing comes from the gonio_spacing attribute, else 1. Throws std::runtime_error naming the
// file when it is missing, corrupt, not square or has no usable channel.
HeightField read_height_exr(const std::string& path, ExrAttributes* attrs = nullptr);

// The most relief a height map may have, in periods (n x spacing) of the patch.
inline constexpr double kMaxReliefOverPeriod = 100;
// What makes a height map no surface to trace (not finite, a relief absurd for its size, heights
// far from 0), or "".
std::string height_map_problem(const HeightField& surface);
// The CRC-32 (zlib) of the heights' and the spacing's bytes, as gonio stores it with its maps.
std::string heights_checksum(const HeightField& surface);

// A multi-channel float image (e.g. measured vs target NDF maps), channels named in `names`,
// each width*height values row-major.
// The surface's normal map: per sample the normal of the slopes (p(x, y), q(x, y)) (its triangle
// A, heightfield.h) as R, G, B; read_height_exr integrates it back into the same heights.
void write_normal_exr(const std::string& path, const HeightField& surface,
                      const ExrAttributes& attrs);

void write_channels_exr(const std::string& path, int width, int height,
                        const std::vector<std::string>& names,
                        const std::vector<std::vector<float>>& channels,
                        const ExrAttributes& attrs);

} // namespace gonio
