#pragma once
// A linear RGB image and its files: PNG (8-bit sRGB, libpng) and OpenEXR (linear float RGB), both
// written under a temporary name and renamed when complete; lat-long EXR environments read back.
#include <array>
#include <string>
#include <vector>

namespace gonio {

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb; // row-major from the top row, 3 per pixel, linear
    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(size_t(w) * size_t(h) * 3, 0.0f) {}
    float* at(int x, int y) { return rgb.data() + (size_t(y) * width + x) * 3; }
    const float* at(int x, int y) const { return rgb.data() + (size_t(y) * width + x) * 3; }
};

// Throw std::runtime_error naming the file.
void write_png(const Image& image, const std::string& path); // clipped to [0, 1], sRGB encoded
void write_exr(const Image& image, const std::string& path);
Image read_exr_rgb(const std::string& path); // R, G, B channels (Y as grey if only Y)

} // namespace gonio
