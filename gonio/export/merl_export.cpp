// MERL .binary (Matusik, Pfister, Brand & McMillan 2003, "A Data-Driven Reflectance Model",
// SIGGRAPH; the layout of their reader MERLBRDFRead.cpp): three int32 dimensions (90, 90, 180) over
// (theta_h, theta_d, phi_d), then three blocks of 1 458 000 float64, red, green and blue, each in
// C order [theta_h][theta_d][phi_d]. theta_h's bins are non-linear, index floor(90 sqrt(theta_h /
// (pi/2))); theta_d and phi_d have 1-degree bins, phi_d over [0, pi) (reciprocity folds the other
// half). Readers multiply by 1/1500, 1.15/1500 and 1.66/1500; negative values mark entries that
// were not measured. gonio writes each bin's value at its centre, from the tabulated BSDF with the
// direction nearer the normal as incidence (reciprocity); a spectral case is converted to linear
// sRGB through the CIE 1931 observer under D65 (core/colour.h).
#include "core/colour.h"
#include "gonio/export/export_formats.h"
#include "gonio/material/ior_table.h"

#include <cstdint>
#include <cstring>

namespace gonio {

namespace {
constexpr int kThetaH = 90, kThetaD = 90, kPhiD = 180;
constexpr double kScale[3] = {1.0 / 1500, 1.15 / 1500, 1.66 / 1500};
constexpr double kInvalid = -1.0;

void put_le(std::ostream& out, const void* p, size_t n) {
    const std::uint16_t one = 1;
    std::uint8_t first;
    std::memcpy(&first, &one, 1);
    if (first == 1) {
        out.write(static_cast<const char*>(p), std::streamsize(n));
        return;
    }
    std::uint8_t b[8];
    std::memcpy(b, p, n);
    for (size_t k = 0; k < n / 2; ++k) std::swap(b[k], b[n - 1 - k]);
    out.write(reinterpret_cast<const char*>(b), std::streamsize(n));
}
} // namespace

static void write_merl(const ResultCase& c, const ExportOptions& o, std::ostream& out,
                       ExportReport& report) {
    const TableOrder order = requested_order(o, false);
    const BsdfTable table = load_table(c, order, "merl");
    if (!table.isotropic())
        throw ExportRefused("merl holds isotropic BRDFs only (phi_h is not one of its "
                            "coordinates): case " +
                            c.name + " is anisotropic");
    require_hemisphere_sweep(table, "merl");
    if (c.transmits)
        report.notes.push_back("the case transmits: the file holds its reflection only");
    const int C = c.channels;
    Matrix3xN to_rgb;
    if (C > 1)
        to_rgb =
            spectrum_to_linear_srgb_matrix(load_colour_tables(data_directory()), c.wavelength_nm);
    const size_t n = size_t(kThetaH) * kThetaD * kPhiD;
    std::vector<double> data(3 * n, kInvalid);
    std::vector<double> f(static_cast<size_t>(C));
    long long unreachable = 0, below = 0, clipped = 0;
    for (int ih = 0; ih < kThetaH; ++ih) {
        const double u = (ih + 0.5) / kThetaH;
        const double theta_h = u * u * (kPi / 2);
        const Vec3 h{std::sin(theta_h), 0, std::cos(theta_h)};
        for (int id = 0; id < kThetaD; ++id) {
            const double theta_d = (id + 0.5) * (kPi / 2) / kThetaD;
            for (int ip = 0; ip < kPhiD; ++ip) {
                const double phi_d = (ip + 0.5) * kPi / kPhiD;
                const Vec3 d = spherical_direction(theta_d, phi_d);
                // wi = R_y(theta_h) d: the inverse of the reader's rotation by -theta_h.
                const Vec3 wi{d.x * std::cos(theta_h) + d.z * std::sin(theta_h), d.y,
                              -d.x * std::sin(theta_h) + d.z * std::cos(theta_h)};
                const Vec3 wo = reflect(wi, h);
                const size_t at = (size_t(ih) * kThetaD + id) * kPhiD + ip;
                if (wi.z <= 0 || wo.z <= 0) {
                    ++below;
                    continue;
                }
                const Vec3& a = wi.z >= wo.z ? wi : wo;
                const Vec3& b = wi.z >= wo.z ? wo : wi;
                if (!table.covers(a)) {
                    ++unreachable;
                    continue;
                }
                table.eval(a, b, f.data());
                std::array<double, 3> rgb = C == 1 ? std::array<double, 3>{f[0], f[0], f[0]}
                                                   : map_channels(to_rgb, f.data());
                for (int ch = 0; ch < 3; ++ch) {
                    if (rgb[ch] < 0) ++clipped, rgb[ch] = 0;
                    data[ch * n + at] = rgb[ch] / kScale[ch];
                }
            }
        }
    }
    const std::int32_t dims[3] = {kThetaH, kThetaD, kPhiD};
    for (std::int32_t v : dims) put_le(out, &v, 4);
    for (double v : data) put_le(out, &v, 8);
    report.notes.push_back(std::to_string(below) + " entries below the horizon and " +
                           std::to_string(unreachable) +
                           " beyond the swept theta_i written as -1 (not measured)");
    if (C > 1) report.notes.push_back("spectral channels converted to linear sRGB (CIE 1931, D65)");
    if (clipped)
        report.notes.push_back(std::to_string(clipped) + " out-of-gamut values clipped to 0");
}

const ExportFormat& merl_format() {
    static const ExportFormat f{
        "merl", "MERL .binary (isotropic reflection, sRGB)", true, false, false, write_merl};
    return f;
}

} // namespace gonio
