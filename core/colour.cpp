#include "core/colour.h"

#include <algorithm>
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

std::array<double, 3> map_channels(const Matrix3xN& m, const double* channels) {
    std::array<double, 3> out{0, 0, 0};
    for (size_t k = 0; k < m.size(); ++k)
        for (int c = 0; c < 3; ++c) out[c] += m[k][c] * channels[k];
    return out;
}

} // namespace gonio
