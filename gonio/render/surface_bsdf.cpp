#include "gonio/render/surface_bsdf.h"

#include "core/colour.h"
#include "gonio/material/ior_table.h"

#include <stdexcept>

namespace gonio {

TableBsdf::TableBsdf(std::shared_ptr<const BsdfTable> table) : table_(std::move(table)) {
    if (table_->channels() != 3) throw std::invalid_argument("TableBsdf: an RGB table expected");
}

Rgb TableBsdf::eval(const Vec3& v, const Vec3& l) const {
    double f[3];
    table_->eval(v, l, f);
    return {f[0], f[1], f[2]};
}

bool TableBsdf::sample(const Vec3& v, double u0, double u1, double u2, Vec3& l, double& pdf) const {
    BsdfTable::Sample s;
    if (!table_->sample(v, u0, u1, u2, s)) return false;
    l = s.wo;
    pdf = s.pdf;
    return true;
}

double TableBsdf::pdf(const Vec3& v, const Vec3& l) const {
    return table_->pdf(v, l);
}

Rgb LambertianBsdf::eval(const Vec3& v, const Vec3& l) const {
    if (v.z <= 0 || l.z <= 0) return {0, 0, 0};
    return {albedo_[0] * kInvPi, albedo_[1] * kInvPi, albedo_[2] * kInvPi};
}

bool LambertianBsdf::sample(const Vec3& v, double, double u1, double u2, Vec3& l,
                            double& pdf) const {
    if (v.z <= 0) return false;
    // Cosine-weighted (Malley): a uniform point on the disk lifted to the hemisphere.
    const double r = std::sqrt(u1), phi = kTwoPi * u2;
    l = {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u1))};
    pdf = l.z * kInvPi;
    return pdf > 0;
}

double LambertianBsdf::pdf(const Vec3& v, const Vec3& l) const {
    return v.z > 0 && l.z > 0 ? l.z * kInvPi : 0;
}

TableData to_linear_srgb(TableData d, const std::vector<double>& wavelengths, long* clipped) {
    const size_t C = size_t(d.channels), n = d.f.size() / C;
    Matrix3xN m;
    if (C > 1)
        m = spectrum_to_linear_srgb_matrix(load_colour_tables(data_directory()), wavelengths);
    std::vector<double> f(n * 3);
    long negative = 0;
    for (size_t k = 0; k < n; ++k) {
        const double* v = d.f.data() + k * C;
        const std::array<double, 3> rgb =
            C == 1 ? std::array<double, 3>{v[0], v[0], v[0]} : map_channels(m, v);
        for (int c = 0; c < 3; ++c) {
            negative += rgb[c] < 0;
            f[k * 3 + c] = std::max(rgb[c], 0.0);
        }
    }
    d.f = std::move(f);
    d.f_stderr.clear();
    d.albedo_stderr.clear();
    d.channels = 3;
    if (clipped) *clipped = negative;
    return d;
}

} // namespace gonio
