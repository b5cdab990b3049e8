#include "gonio/render/colour_difference.h"

#include "core/colour.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace gonio {

std::vector<double> delta_e00(const Image& a, const Image& b) {
    std::vector<double> out(size_t(a.width) * a.height, 0.0);
    auto lab = [](const float* p) {
        return xyz_to_lab(linear_srgb_to_xyz({std::clamp(double(p[0]), 0.0, 1.0),
                                              std::clamp(double(p[1]), 0.0, 1.0),
                                              std::clamp(double(p[2]), 0.0, 1.0)}));
    };
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            out[size_t(y) * a.width + x] = ciede2000(lab(a.at(x, y)), lab(b.at(x, y)));
    return out;
}

DifferenceStats difference_stats(const std::vector<double>& de,
                                 const std::vector<std::uint8_t>& mask) {
    std::vector<double> v;
    for (size_t k = 0; k < de.size(); ++k)
        if (mask[k]) v.push_back(de[k]);
    DifferenceStats s;
    s.pixels = (long long)v.size();
    if (v.empty()) return s;
    std::sort(v.begin(), v.end());
    double sum = 0;
    for (double x : v) sum += x;
    s.mean = sum / double(v.size());
    s.p95 = v[std::min(v.size() - 1, size_t(0.95 * double(v.size())))];
    s.max = v.back();
    return s;
}

std::array<float, 3> false_colour_of(double value, double scale) {
    // A jet-like ramp: blue, cyan, green, yellow, red at 0, 1/4, 1/2, 3/4, 1 of the scale.
    static const float stops[5][3] = {
        {0, 0, 0.6f}, {0, 0.8f, 1}, {0, 0.8f, 0}, {1, 0.9f, 0}, {0.9f, 0, 0}};
    const double t = std::clamp(value / scale, 0.0, 1.0) * 4;
    const int k = std::min(int(t), 3);
    const double f = t - k;
    std::array<float, 3> c;
    for (int i = 0; i < 3; ++i) c[i] = float(stops[k][i] + (stops[k + 1][i] - stops[k][i]) * f);
    return c;
}

namespace {
// Digits 3 x 5, one row per entry, bit 2 the left pixel.
const unsigned char kDigits[10][5] = {
    {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
    {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};
void draw_text(Image& img, int x, int y, const std::string& text, int scale) {
    for (char ch : text) {
        if (ch < '0' || ch > '9') continue;
        const auto& g = kDigits[ch - '0'];
        for (int r = 0; r < 5; ++r)
            for (int c = 0; c < 3; ++c)
                if (g[r] & (4 >> c))
                    for (int dy = 0; dy < scale; ++dy)
                        for (int dx = 0; dx < scale; ++dx) {
                            const int px = x + c * scale + dx, py = y + r * scale + dy;
                            if (px >= 0 && px < img.width && py >= 0 && py < img.height)
                                std::fill(img.at(px, py), img.at(px, py) + 3, 1.0f);
                        }
        x += 4 * scale;
    }
}
} // namespace

Image false_colour(const std::vector<double>& de, int width, int height, double scale) {
    const int bar = std::max(24, height / 10), text = std::max(1, bar / 12);
    Image img(width, height + bar);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const auto c = false_colour_of(de[size_t(y) * width + x], scale);
            std::copy(c.begin(), c.end(), img.at(x, y));
        }
    // The bar: the ramp over 80 % of the width, ticks and labels at 0, 1, 3, 5 and 10.
    const int x0 = width / 10, x1 = width - width / 10, y0 = height + bar / 6,
              y1 = height + bar / 2;
    for (int x = x0; x < x1; ++x) {
        const auto c = false_colour_of(scale * (x - x0) / double(x1 - x0 - 1), scale);
        for (int y = y0; y < y1; ++y) std::copy(c.begin(), c.end(), img.at(x, y));
    }
    for (double tick : {0.0, 1.0, 3.0, 5.0, 10.0}) {
        if (tick > scale) continue;
        const int x = x0 + int(std::lround(tick / scale * (x1 - x0 - 1)));
        for (int y = y1; y < y1 + bar / 8 && y < img.height; ++y)
            std::fill(img.at(x, y), img.at(x, y) + 3, 1.0f);
        const std::string label = std::to_string(int(tick));
        draw_text(img, x - int(label.size()) * 2 * text, y1 + bar / 8 + 1, label, text);
    }
    return img;
}

} // namespace gonio
