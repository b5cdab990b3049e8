#include "gonio/render/environment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

Environment::Environment(Image map) : map_(std::move(map)) {
    const int w = map_.width, h = map_.height;
    if (w < 1 || h < 1) throw std::invalid_argument("Environment: an empty map");
    texel_p_.assign(size_t(w) * h, 0.0);
    column_cdf_.assign(size_t(h) * (w + 1), 0.0);
    row_cdf_.assign(size_t(h) + 1, 0.0);
    for (int y = 0; y < h; ++y) {
        const double sin_theta = std::sin(kPi * (y + 0.5) / h);
        double row = 0;
        for (int x = 0; x < w; ++x) {
            const float* c = map_.at(x, y);
            if (!std::isfinite(c[0] + c[1] + c[2]))
                throw std::invalid_argument("Environment: a texel is not a finite number");
            const double lum = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
            // A floor keeps every texel reachable, so the pdf is positive wherever eval is.
            texel_p_[size_t(y) * w + x] = (std::max(lum, 0.0) + 1e-6) * sin_theta;
            row += texel_p_[size_t(y) * w + x];
            column_cdf_[size_t(y) * (w + 1) + x + 1] = row;
        }
        row_cdf_[y + 1] = row_cdf_[y] + row;
    }
    const double total = row_cdf_.back();
    for (double& p : texel_p_) p /= total;
}

Environment Environment::uniform(double radiance) {
    Image m(64, 32);
    std::fill(m.rgb.begin(), m.rgb.end(), float(radiance));
    return Environment(std::move(m));
}

Environment Environment::overcast_sky() {
    Image m(256, 128);
    for (int y = 0; y < m.height; ++y) {
        const double cos_theta = std::cos(kPi * (y + 0.5) / m.height);
        const double l = cos_theta > 0 ? (1 + 2 * cos_theta) / 3 : 0.1;
        for (int x = 0; x < m.width; ++x)
            for (int c = 0; c < 3; ++c) m.at(x, y)[c] = float(l);
    }
    return Environment(std::move(m));
}

Environment Environment::from_exr(const std::string& path) {
    return Environment(read_exr_rgb(path));
}

void Environment::texel(const Vec3& d, int& x, int& y) const {
    const double u = spherical_phi(d) / kTwoPi, v = spherical_theta(d) / kPi;
    x = std::clamp(int(u * map_.width), 0, map_.width - 1);
    y = std::clamp(int(v * map_.height), 0, map_.height - 1);
}

Rgb Environment::radiance(const Vec3& d) const {
    int x, y;
    texel(d, x, y);
    const float* c = map_.at(x, y);
    return {c[0], c[1], c[2]};
}

Vec3 Environment::sample(double u1, double u2, double& pdf) const {
    const int w = map_.width, h = map_.height;
    const double total = row_cdf_.back();
    double t = u1 * total;
    int y = int(std::upper_bound(row_cdf_.begin(), row_cdf_.end(), t) - row_cdf_.begin()) - 1;
    y = std::clamp(y, 0, h - 1);
    const double row = row_cdf_[y + 1] - row_cdf_[y];
    const double fy = row > 0 ? std::clamp((t - row_cdf_[y]) / row, 0.0, 1.0) : 0.5;
    const double* cdf = column_cdf_.data() + size_t(y) * (w + 1);
    t = u2 * cdf[w];
    int x = int(std::upper_bound(cdf, cdf + w + 1, t) - cdf) - 1;
    x = std::clamp(x, 0, w - 1);
    const double cell = cdf[x + 1] - cdf[x];
    const double fx = cell > 0 ? std::clamp((t - cdf[x]) / cell, 0.0, 1.0) : 0.5;
    // Uniform in (phi, cos theta) within the texel: the texel's solid angle is exact.
    const double phi = kTwoPi * (x + fx) / w;
    const double z0 = std::cos(kPi * y / h), z1 = std::cos(kPi * (y + 1) / h);
    const double z = z0 + fy * (z1 - z0), r = std::sqrt(std::max(0.0, 1 - z * z));
    const Vec3 d{r * std::cos(phi), r * std::sin(phi), z};
    pdf = texel_p_[size_t(y) * w + x] / ((z0 - z1) * kTwoPi / w);
    return d;
}

double Environment::pdf(const Vec3& d) const {
    int x, y;
    texel(d, x, y);
    const int w = map_.width, h = map_.height;
    const double z0 = std::cos(kPi * y / h), z1 = std::cos(kPi * (y + 1) / h);
    return texel_p_[size_t(y) * w + x] / ((z0 - z1) * kTwoPi / w);
}

Environment Environment::named(const std::string& text) {
    if (text == "uniform") return uniform(1.0);
    if (text == "sky") return overcast_sky();
    return from_exr(text);
}

} // namespace gonio
