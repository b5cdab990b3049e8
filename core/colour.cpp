#include "core/colour.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {
// Rows of numbers from a CSV with '#' comments and one header line.
std::vector<std::vector<double>> read_csv(const std::string& path, size_t columns) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open (colour tables)");
    std::vector<std::vector<double>> rows;
    std::string line;
    bool header = true;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (header) {
            header = false;
            continue;
        }
        std::vector<double> row;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) row.push_back(std::stod(cell));
        if (row.size() != columns)
            throw std::runtime_error(path + ": a row of " + std::to_string(row.size()) +
                                     " columns, expected " + std::to_string(columns));
        rows.push_back(row);
    }
    return rows;
}
} // namespace

ColourTables load_colour_tables(const std::string& data_dir) {
    const std::string cmf_path = data_dir + "/cie/cie1931_2deg.csv";
    const std::string d65_path = data_dir + "/cie/d65.csv";
    const auto cmf = read_csv(cmf_path, 4);
    const auto d65 = read_csv(d65_path, 2);
    if (cmf.size() != d65.size())
        throw std::runtime_error(d65_path + ": not on the wavelengths of " + cmf_path);
    ColourTables t;
    for (size_t k = 0; k < cmf.size(); ++k) {
        if (cmf[k][0] != d65[k][0])
            throw std::runtime_error(d65_path + ": not on the wavelengths of " + cmf_path);
        t.wavelength_nm.push_back(cmf[k][0]);
        t.x_bar.push_back(cmf[k][1]);
        t.y_bar.push_back(cmf[k][2]);
        t.z_bar.push_back(cmf[k][3]);
        t.d65.push_back(d65[k][1]);
    }
    return t;
}

Matrix3xN spectrum_to_xyz_matrix(const ColourTables& t, const std::vector<double>& wl) {
    if (wl.empty()) throw std::invalid_argument("spectrum_to_xyz_matrix: no wavelengths");
    for (size_t k = 1; k < wl.size(); ++k)
        if (wl[k] == wl[k - 1])
            throw std::invalid_argument("spectrum_to_xyz_matrix: a wavelength appears twice");
    // Channels sorted by wavelength; the spectrum at each table wavelength is a convex combination
    // of at most two channels (hat functions), so the map is linear in the channel values.
    std::vector<size_t> order(wl.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return wl[a] < wl[b]; });
    Matrix3xN m(wl.size(), {0.0, 0.0, 0.0});
    double white_y = 0;
    for (size_t s = 0; s < t.wavelength_nm.size(); ++s) {
        const double lambda = t.wavelength_nm[s];
        const std::array<double, 3> w{t.d65[s] * t.x_bar[s], t.d65[s] * t.y_bar[s],
                                      t.d65[s] * t.z_bar[s]};
        white_y += w[1];
        auto add = [&](size_t channel, double weight) {
            for (int c = 0; c < 3; ++c) m[channel][c] += weight * w[c];
        };
        if (lambda <= wl[order.front()]) {
            add(order.front(), 1);
        } else if (lambda >= wl[order.back()]) {
            add(order.back(), 1);
        } else {
            size_t k = 0;
            while (wl[order[k + 1]] < lambda) ++k;
            const double a = wl[order[k]], b = wl[order[k + 1]];
            const double f = (lambda - a) / (b - a);
            add(order[k], 1 - f);
            add(order[k + 1], f);
        }
    }
    for (auto& column : m)
        for (double& v : column) v /= white_y;
    return m;
}

std::array<double, 3> xyz_to_linear_srgb(const std::array<double, 3>& c) {
    // IEC 61966-2-1 (sRGB), D65 white.
    return {3.2406 * c[0] - 1.5372 * c[1] - 0.4986 * c[2],
            -0.9689 * c[0] + 1.8758 * c[1] + 0.0415 * c[2],
            0.0557 * c[0] - 0.2040 * c[1] + 1.0570 * c[2]};
}

Matrix3xN spectrum_to_linear_srgb_matrix(const ColourTables& t, const std::vector<double>& wl) {
    Matrix3xN m = spectrum_to_xyz_matrix(t, wl);
    for (auto& column : m) column = xyz_to_linear_srgb(column);
    return m;
}

std::array<double, 3> linear_srgb_to_xyz(const std::array<double, 3>& c) {
    // IEC 61966-2-1: the inverse of the matrix above.
    return {0.4124 * c[0] + 0.3576 * c[1] + 0.1805 * c[2],
            0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2],
            0.0193 * c[0] + 0.1192 * c[1] + 0.9505 * c[2]};
}

std::array<double, 3> xyz_to_lab(const std::array<double, 3>& xyz) {
    constexpr double white[3] = {0.95047, 1.0, 1.08883}; // D65, 2-degree observer
    auto f = [](double t) {
        constexpr double d = 6.0 / 29;
        return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29;
    };
    const double fx = f(xyz[0] / white[0]), fy = f(xyz[1] / white[1]), fz = f(xyz[2] / white[2]);
    return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

double srgb_encode(double v) {
    v = std::clamp(v, 0.0, 1.0);
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

double ciede2000(const std::array<double, 3>& lab1, const std::array<double, 3>& lab2) {
    constexpr double pi = 3.14159265358979323846;
    const auto deg = [](double r) { return r * 180 / pi; };
    const auto rad = [](double d) { return d * pi / 180; };
    const double L1 = lab1[0], a1 = lab1[1], b1 = lab1[2], L2 = lab2[0], a2 = lab2[1], b2 = lab2[2];
    // Eqs. 2-6: a' stretched by G from the mean chroma.
    const double C_mean = 0.5 * (std::hypot(a1, b1) + std::hypot(a2, b2));
    const double c7 = std::pow(C_mean, 7);
    const double G = 0.5 * (1 - std::sqrt(c7 / (c7 + std::pow(25.0, 7))));
    const double a1p = (1 + G) * a1, a2p = (1 + G) * a2;
    const double C1p = std::hypot(a1p, b1), C2p = std::hypot(a2p, b2);
    auto hue = [&](double b, double ap) {
        if (b == 0 && ap == 0) return 0.0;
        const double h = deg(std::atan2(b, ap));
        return h < 0 ? h + 360 : h;
    };
    const double h1p = hue(b1, a1p), h2p = hue(b2, a2p);
    // Eqs. 8-12: differences.
    const double dLp = L2 - L1, dCp = C2p - C1p;
    double dhp = 0;
    if (C1p * C2p != 0) {
        dhp = h2p - h1p;
        if (dhp > 180) dhp -= 360;
        else if (dhp < -180) dhp += 360;
    }
    const double dHp = 2 * std::sqrt(C1p * C2p) * std::sin(rad(dhp / 2));
    // Eqs. 13-21: weights and rotation.
    const double Lbp = 0.5 * (L1 + L2), Cbp = 0.5 * (C1p + C2p);
    double hbp = h1p + h2p;
    if (C1p * C2p != 0) {
        if (std::abs(h1p - h2p) <= 180) hbp = 0.5 * (h1p + h2p);
        else if (h1p + h2p < 360) hbp = 0.5 * (h1p + h2p + 360);
        else hbp = 0.5 * (h1p + h2p - 360);
    }
    const double T = 1 - 0.17 * std::cos(rad(hbp - 30)) + 0.24 * std::cos(rad(2 * hbp)) +
                     0.32 * std::cos(rad(3 * hbp + 6)) - 0.20 * std::cos(rad(4 * hbp - 63));
    const double dtheta = 30 * std::exp(-std::pow((hbp - 275) / 25, 2));
    const double cb7 = std::pow(Cbp, 7);
    const double RC = 2 * std::sqrt(cb7 / (cb7 + std::pow(25.0, 7)));
    const double SL = 1 + 0.015 * (Lbp - 50) * (Lbp - 50) / std::sqrt(20 + (Lbp - 50) * (Lbp - 50));
    const double SC = 1 + 0.045 * Cbp, SH = 1 + 0.015 * Cbp * T;
    const double RT = -std::sin(rad(2 * dtheta)) * RC;
    const double l = dLp / SL, c = dCp / SC, h = dHp / SH;
    return std::sqrt(l * l + c * c + h * h + RT * c * h);
}

std::array<double, 3> map_channels(const Matrix3xN& m, const double* channels) {
    std::array<double, 3> out{0, 0, 0};
    for (size_t k = 0; k < m.size(); ++k)
        for (int c = 0; c < 3; ++c) out[c] += m[k][c] * channels[k];
    return out;
}

} // namespace gonio
