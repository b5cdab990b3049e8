// The RGL measured-BSDF tensor file (Dupuy & Jakob 2018, "An Adaptive Parameterization for
// Efficient Material Acquisition and Rendering", ACM TOG 37(6)), as Mitsuba 3's and pbrt-v4's
// `measured` BSDFs read it. With w_p the parameter direction (the incidence of the table) and
// u_m = (theta2u(theta_m), phi2u(phi_m)) of the half vector m, a reader evaluates
//   f cos theta_q = spectra(vndf^-1(u_m)) ndf(u_m) / (4 sigma(w_p))      [D&J 2018 Eq. 9 and Sec.
//   5]
// so the file stores spectra = f cos theta_q 4 sigma / D at the points the VNDF warp of each
// incidence reaches from a regular grid of its unit square, where f is the tabulated BSDF.
//
// Which D: the case's own NDF (what the surfaces were generated to follow; analytic, noise free
// and symmetric, where the traced height map's facet histogram is noisy and differs per surface
// of an ensemble), resolved to the sensor's cells (an NDF narrower than the cells is smoothed to
// their size, since the table cannot hold a narrower lobe and the warp must spread the file's
// samples over the lobe the table does hold), plus a 2 % cosine-weighted floor so that the
// multiply scattered light far from the specular half vectors stays reachable. D only shapes the
// parameterisation: the values come from the table whichever D is chosen, since the stored ratio
// divides by the same D and sigma the reader multiplies by.
#include "core/colour.h"
#include "gonio/export/export_formats.h"
#include "gonio/export/piecewise_linear_2d.h"
#include "gonio/export/tensor_file.h"
#include "gonio/material/ior_table.h"
#include "gonio_version.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace gonio {

namespace {
constexpr int kNdfWidth = 128;  // theta2u vertices of ndf, sigma and vndf
constexpr int kPhiHeight = 128; // phi vertices of vndf (and of ndf when anisotropic)
constexpr int kSigmaAniso = 64; // sigma's grid of an anisotropic file
constexpr int kSampleRes = 64;  // luminance and spectra vertices per side (published: 32)
constexpr double kFloor = 0.02; // share of the cosine-weighted floor in the file's D

double theta2u(double t) {
    return std::sqrt(t * 2 / kPi);
}
double phi2u(double p) {
    return (p + kPi) / kTwoPi;
}
double u2theta(double u) {
    return u * u * kPi / 2;
}
double u2phi(double u) {
    return (2 * u - 1) * kPi;
}
Vec3 direction_of(double u_x, double u_y, double phi_offset) {
    return spherical_direction(u2theta(u_x), u2phi(u_y) + phi_offset);
}
// d omega_m = 2 pi^2 u_x sin theta_m du_x du_y.
double jacobian(double u_x) {
    return 2 * kPi * kPi * u_x * std::sin(u2theta(u_x));
}

// The case's D resolved to an angular scale `beta`: itself when its narrowest feature is wider
// than 2 beta, else a Gaussian kernel estimate from its own samples (all near its peak).
class ResolvedNdf {
  public:
    ResolvedNdf(const Ndf& ndf, double beta) : ndf_(ndf), beta_(beta) {
        if (ndf.narrowest_feature() >= 2 * beta) return;
        const int n = 64;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                samples_.push_back(ndf.sample_m((i + 0.5) / n, (j + 0.5) / n));
    }
    bool smoothed() const { return !samples_.empty(); }
    double D(const Vec3& m) const {
        if (samples_.empty()) return ndf_.D(m);
        // D~(m) = E[K(m, m') / m'.z] over m' with pdf D(m') m'.z; K a unit-mass Gaussian in angle.
        double sum = 0;
        const double norm = 1 / (kTwoPi * beta_ * beta_);
        for (const Vec3& s : samples_) {
            const double a = angle_between(m, s);
            if (a < 6 * beta_) sum += norm * std::exp(-0.5 * a * a / (beta_ * beta_)) / s.z;
        }
        return sum / double(samples_.size());
    }

  private:
    const Ndf& ndf_;
    double beta_;
    std::vector<Vec3> samples_;
};

// Luminance weights per channel: the Y of the stored value (sampling needs only its shape).
std::vector<double> luminance_weights(const ResultCase& c, bool rgb) {
    if (rgb) return {0.2126, 0.7152, 0.0722};
    if (c.channels == 1) return {1.0};
    const Matrix3xN m =
        spectrum_to_xyz_matrix(load_colour_tables(data_directory()), c.wavelength_nm);
    std::vector<double> w;
    for (const auto& column : m) w.push_back(std::max(column[1], 0.0));
    return w;
}
} // namespace

static void write_rgl(const ResultCase& c, const ExportOptions& o, std::ostream& out,
                      ExportReport& report) {
    const TableOrder order = requested_order(o, false);
    const BsdfTable table = load_table(c, order, "rgl");
    require_hemisphere_sweep(table, "rgl");
    if (c.transmits)
        report.notes.push_back("the case transmits: the file holds its reflection only");
    const bool iso = table.isotropic();
    const int C = c.channels;

    // Parameter grid: the swept theta_i; phi_i one entry (isotropic) or the full turn [-pi, pi].
    std::vector<double> theta_p, phi_p;
    for (double t : table.theta_nodes()) theta_p.push_back(radians(t));
    if (iso) {
        phi_p = {0.0};
    } else {
        phi_p.push_back(-kPi);
        for (double p : table.phi_nodes()) {
            const double q = radians(p > 180 ? p - 360 : p);
            if (q > -kPi + 1e-9 && q < kPi - 1e-9) phi_p.push_back(q);
        }
        std::sort(phi_p.begin() + 1, phi_p.end());
        phi_p.push_back(kPi);
    }
    const size_t nt = theta_p.size(), np = phi_p.size();

    // The file's D on the ndf grid (isotropic: two identical rows), normalised so that
    // integral D cos theta_m d omega = 1 for the interpolant the readers evaluate.
    const double cell_angle = std::sqrt(kTwoPi / c.cells);
    const ResolvedNdf resolved(*c.config.ndf, cell_angle);
    if (resolved.smoothed())
        report.notes.push_back("the NDF is narrower than the sensor's cells: the file's ndf is "
                               "the NDF smoothed to their size");
    const int ndf_h = iso ? 2 : kPhiHeight;
    std::vector<double> ndf(size_t(ndf_h) * kNdfWidth);
    for (int y = 0; y < ndf_h; ++y)
        for (int x = 0; x < kNdfWidth; ++x) {
            const Vec3 m = direction_of(x / double(kNdfWidth - 1), y / double(ndf_h - 1), 0);
            ndf[size_t(y) * kNdfWidth + x] = (1 - kFloor) * resolved.D(m) + kFloor * kInvPi;
        }
    // Quadrature of the interpolant: midpoints of a grid 4 times finer than the ndf's.
    struct Node {
        Vec3 m;
        double u_x, u_y, weight; // weight: d omega of the quadrature cell
    };
    const int qx = 4 * (kNdfWidth - 1), qy = iso ? 128 : 2 * (kPhiHeight - 1);
    std::vector<Node> quad;
    quad.reserve(size_t(qx) * qy);
    for (int j = 0; j < qy; ++j)
        for (int i = 0; i < qx; ++i) {
            const double ux = (i + 0.5) / qx, uy = (j + 0.5) / qy;
            quad.push_back({direction_of(ux, uy, 0), ux, uy, jacobian(ux) / (double(qx) * qy)});
        }
    {
        const PiecewiseLinear2D raw(ndf, kNdfWidth, ndf_h, false);
        double integral = 0;
        for (const Node& q : quad) integral += raw.eval({q.u_x, q.u_y}) * q.m.z * q.weight;
        for (double& v : ndf) v /= integral;
    }
    const PiecewiseLinear2D ndf_eval(ndf, kNdfWidth, ndf_h, false);
    std::vector<double> d_at_quad(quad.size());
    for (size_t k = 0; k < quad.size(); ++k)
        d_at_quad[k] = ndf_eval.eval({quad[k].u_x, quad[k].u_y});

    // sigma(w) = integral D(m) <w.m> d omega_m, on its own grid of w.
    const int sig_w = iso ? kNdfWidth : kSigmaAniso, sig_h = iso ? 2 : kSigmaAniso;
    std::vector<double> sigma(size_t(sig_w) * sig_h);
    for (int y = 0; y < sig_h; ++y)
        for (int x = 0; x < sig_w; ++x) {
            const Vec3 w = direction_of(x / double(sig_w - 1), y / double(sig_h - 1), 0);
            double s = 0;
            for (size_t k = 0; k < quad.size(); ++k)
                s += d_at_quad[k] * std::max(0.0, dot(w, quad[k].m)) * quad[k].weight;
            sigma[size_t(y) * sig_w + x] = s;
        }
    const PiecewiseLinear2D sigma_eval(sigma, sig_w, sig_h, false);

    // Per incidence: the VNDF slice, then the stored ratio at the points it warps the sample
    // grid to, and its luminance for sampling.
    const std::vector<double> lum_w = luminance_weights(c, o.rgb);
    const int out_channels = o.rgb ? 3 : std::max(C, 2);
    Matrix3xN to_rgb;
    if (o.rgb && C > 1)
        to_rgb =
            spectrum_to_linear_srgb_matrix(load_colour_tables(data_directory()), c.wavelength_nm);
    // Spectral channels in increasing wavelength (the readers search them).
    std::vector<int> channel_order(static_cast<size_t>(C));
    std::iota(channel_order.begin(), channel_order.end(), 0);
    if (C > 1)
        std::sort(channel_order.begin(), channel_order.end(),
                  [&](int a, int b) { return c.wavelength_nm[a] < c.wavelength_nm[b]; });
    const size_t slice_v = size_t(kPhiHeight) * kNdfWidth,
                 slice_s = size_t(kSampleRes) * kSampleRes;
    std::vector<double> vndf(np * nt * slice_v), luminance(np * nt * slice_s),
        values(np * nt * size_t(out_channels) * slice_s);
    int negative_rgb = 0;
    std::vector<double> f(static_cast<size_t>(C));
    for (size_t k = 0; k < np; ++k)
        for (size_t j = 0; j < nt; ++j) {
            const Vec3 wp = spherical_direction(theta_p[j], phi_p[k]);
            const double offset = iso ? phi_p[k] : 0.0;
            double* v = vndf.data() + (k * nt + j) * slice_v;
            for (int y = 0; y < kPhiHeight; ++y)
                for (int x = 0; x < kNdfWidth; ++x) {
                    const double ux = x / double(kNdfWidth - 1), uy = y / double(kPhiHeight - 1);
                    const Vec3 m = direction_of(ux, uy, offset);
                    v[size_t(y) * kNdfWidth + x] =
                        jacobian(ux) * std::max(0.0, dot(wp, m)) * ndf_eval.eval({ux, uy});
                }
            const PiecewiseLinear2D warp(std::vector<double>(v, v + slice_v), kNdfWidth, kPhiHeight,
                                         true);
            const double sig = sigma_eval.eval({theta2u(theta_p[j]), phi2u(phi_p[k])});
            double* lum = luminance.data() + (k * nt + j) * slice_s;
            double* val = values.data() + (k * nt + j) * size_t(out_channels) * slice_s;
            for (int y = 0; y < kSampleRes; ++y)
                for (int x = 0; x < kSampleRes; ++x) {
                    const auto um =
                        warp.sample({x / double(kSampleRes - 1), y / double(kSampleRes - 1)});
                    const Vec3 m = direction_of(um[0], um[1], offset);
                    const Vec3 wq = reflect(wp, m);
                    const size_t at = size_t(y) * kSampleRes + x;
                    double l = 0;
                    if (wq.z > 0) {
                        table.eval(wp, wq, f.data());
                        const double ratio = wq.z * 4 * sig / ndf_eval.eval(um);
                        std::vector<double> stored(static_cast<size_t>(out_channels));
                        if (o.rgb) {
                            const std::array<double, 3> rgb =
                                C == 1 ? std::array<double, 3>{f[0], f[0], f[0]}
                                       : map_channels(to_rgb, f.data());
                            for (int ch = 0; ch < 3; ++ch) {
                                negative_rgb += rgb[ch] < 0;
                                stored[ch] = std::max(rgb[ch], 0.0) * ratio;
                            }
                        } else if (C == 1) {
                            stored[0] = stored[1] = f[0] * ratio;
                        } else {
                            for (int ch = 0; ch < C; ++ch)
                                stored[ch] = f[channel_order[ch]] * ratio;
                        }
                        for (int ch = 0; ch < out_channels; ++ch) {
                            val[size_t(ch) * slice_s + at] = stored[ch];
                            if (!o.rgb && C > 1) l += lum_w[channel_order[ch]] * stored[ch];
                        }
                        if (o.rgb)
                            l = lum_w[0] * stored[0] + lum_w[1] * stored[1] + lum_w[2] * stored[2];
                        else if (C == 1)
                            l = stored[0];
                    }
                    lum[at] = l;
                }
            // A slice with nothing to sample: uniform, so that the readers' warp stays defined.
            if (std::all_of(lum, lum + slice_s, [](double x) { return x <= 0; }))
                std::fill(lum, lum + slice_s, 1.0);
        }
    if (negative_rgb > 0)
        report.notes.push_back(std::to_string(negative_rgb) +
                               " sRGB values outside the gamut were clipped to 0");

    TensorFileWriter w;
    const std::string description =
        "gonio " + std::string(kVersion) + " (git " + kGitHash + "): case " + c.name + " of " +
        c.file + ", order " + name_of(order) + ", " + std::to_string(c.cells) + " sensor cells; " +
        (iso ? "isotropic" : "anisotropic") + "; ndf: the case's NDF" +
        (resolved.smoothed() ? " smoothed to the sensor's cells" : "") + " with a 2% cosine floor";
    w.add_u8("description", {description.size()},
             std::vector<std::uint8_t>(description.begin(), description.end()));
    w.add_u8("jacobian", {1}, {1});
    w.add_f32("theta_i", {nt}, theta_p);
    w.add_f32("phi_i", {np}, phi_p);
    w.add_f32("ndf", {std::uint64_t(ndf_h), kNdfWidth}, ndf);
    w.add_f32("sigma", {std::uint64_t(sig_h), std::uint64_t(sig_w)}, sigma);
    w.add_f32("vndf", {np, nt, kPhiHeight, kNdfWidth}, vndf);
    w.add_f32("luminance", {np, nt, kSampleRes, kSampleRes}, luminance);
    if (o.rgb) {
        w.add_f32("rgb", {np, nt, 3, kSampleRes, kSampleRes}, values);
    } else {
        std::vector<double> wl;
        if (C == 1)
            wl = {360, 830}; // achromatic: one value at every wavelength
        else
            for (int ch : channel_order) wl.push_back(c.wavelength_nm[ch]);
        w.add_f32("wavelengths", {wl.size()}, wl);
        w.add_f32("spectra", {np, nt, std::uint64_t(out_channels), kSampleRes, kSampleRes}, values);
    }
    w.write(out);
}

const ExportFormat& rgl_format() {
    static const ExportFormat f{
        "rgl", "RGL tensor file (Mitsuba 3 / pbrt-v4 `measured`)", true, true, false, write_rgl};
    return f;
}

} // namespace gonio
