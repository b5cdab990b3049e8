#include "heightfield/ndf/ndf_table.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {
[[noreturn]] void fail(const std::string& path, const std::string& problem) {
    throw std::runtime_error("NDF table " + path + ": " + problem);
}

bool is_hdf5(const std::string& path) {
    for (const char* ext : {".h5", ".hdf5"}) {
        const std::string e(ext);
        if (path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0)
            return true;
    }
    return false;
}

NdfTable read_text(const std::string& path) {
    std::ifstream in(path);
    if (!in) fail(path, "cannot open");
    NdfTable t;
    std::string line;
    int row = 0, lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        line = line.substr(0, line.find('#'));
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream s(line);
        std::vector<double> v;
        std::string word;
        while (s >> word) {
            size_t used = 0;
            double x = 0;
            try {
                x = std::stod(word, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != word.size())
                fail(path, "line " + std::to_string(lineno) + ": '" + word + "' is not a number");
            v.push_back(x);
        }
        if (v.empty()) continue;
        if (t.phi_count == 0) t.phi_count = int(v.size());
        if (int(v.size()) != t.phi_count)
            fail(path, "line " + std::to_string(lineno) + " has " + std::to_string(v.size()) +
                           " values, the first row " + std::to_string(t.phi_count));
        t.values.insert(t.values.end(), v.begin(), v.end());
        ++row;
    }
    t.theta_intervals = row - 1;
    return t;
}

NdfTable read_hdf5(const std::string& path) {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file < 0) fail(path, "cannot open as HDF5");
    NdfTable t;
    int rank = 0;
    herr_t ok = H5LTget_dataset_ndims(file, "D", &rank);
    if (ok < 0 || rank != 2) {
        H5Fclose(file);
        fail(path, "needs a 2-D dataset \"D\" (theta rows, phi columns)");
    }
    hsize_t dims[2] = {0, 0};
    H5LTget_dataset_info(file, "D", dims, nullptr, nullptr);
    if (dims[0] > 100000 || dims[1] > 100000 || dims[0] * dims[1] > 10000000) {
        H5Fclose(file);
        fail(path, "dataset \"D\" is larger than 10^7 values");
    }
    t.values.resize(size_t(dims[0] * dims[1]));
    ok = H5LTread_dataset_double(file, "D", t.values.data());
    H5Fclose(file);
    if (ok < 0) fail(path, "cannot read dataset \"D\" as doubles");
    t.theta_intervals = int(dims[0]) - 1;
    t.phi_count = int(dims[1]);
    return t;
}
} // namespace

NdfTable read_ndf_table(const std::string& path) {
    NdfTable t = is_hdf5(path) ? read_hdf5(path) : read_text(path);
    if (t.theta_intervals < 2) fail(path, "needs at least 3 theta rows (0 to 90 degrees)");
    if (t.phi_count < 1) fail(path, "needs at least one phi column");
    for (double v : t.values)
        if (!(v >= 0) || !std::isfinite(v)) fail(path, "values must be finite and >= 0");
    return t;
}

NdfTable sample_ndf_table(const Ndf& ndf, int theta_intervals, int phi_count) {
    NdfTable t{theta_intervals, phi_count, {}};
    for (int j = 0; j <= theta_intervals; ++j)
        for (int k = 0; k < phi_count; ++k)
            t.values.push_back(ndf.D(
                spherical_direction(std::min(0.5 * kPi * j / theta_intervals, 0.5 * kPi - 1e-9),
                                    kTwoPi * k / phi_count)));
    return t;
}

NdfTable facet_ndf_table(const HeightField& s, int theta_intervals, int phi_count) {
    // Equal projected areas: every triangle weighs the same in D cos.
    std::vector<Vec3> normals;
    normals.reserve(size_t(2) * s.n * s.n);
    for (int y = 0; y < s.n; ++y)
        for (int x = 0; x < s.n; ++x)
            for (int tri = 0; tri < 2; ++tri) {
                double sp, sq;
                s.triangle_slopes(x, y, tri, sp, sq);
                normals.push_back(HeightField::normal_of_slopes(sp, sq));
            }
    return ndf_table_of_normals(normals, theta_intervals, phi_count);
}

NdfTable ndf_table_of_normals(const std::vector<Vec3>& normals, int theta_intervals,
                              int phi_count) {
    NdfTable t;
    t.theta_intervals = theta_intervals;
    t.phi_count = phi_count;
    const int rows = theta_intervals + 1;
    std::vector<double> mass(size_t(rows) * phi_count, 0.0);
    const double dt = 0.5 * kPi / theta_intervals, dp = kTwoPi / phi_count;
    for (const Vec3& m : normals) {
        const double theta = std::acos(std::clamp(m.z, -1.0, 1.0));
        double phi = std::atan2(m.y, m.x);
        if (phi < 0) phi += kTwoPi;
        const double ft = std::min(theta / dt, double(theta_intervals) - 1e-9), fp = phi / dp;
        const int j = int(ft), k = int(fp) % phi_count;
        const double a = ft - j, b = fp - std::floor(fp);
        mass[size_t(j) * phi_count + k] += (1 - a) * (1 - b);
        mass[size_t(j) * phi_count + (k + 1) % phi_count] += (1 - a) * b;
        mass[size_t(j + 1) * phi_count + k] += a * (1 - b);
        mass[size_t(j + 1) * phi_count + (k + 1) % phi_count] += a * b;
    }
    // Each node's measure: int hat_j(theta) cos sin dtheta times dp (the phi hat integrates to dp).
    auto hat_measure = [&](int j) {
        auto part = [&](double a, double b, bool rising) { // int of the linear hat on [a, b]
            double sum = 0;
            const int nodes = 16;
            for (int i = 0; i < nodes; ++i) {
                const double th = a + (b - a) * (i + 0.5) / nodes;
                const double w = rising ? (th - a) / (b - a) : (b - th) / (b - a);
                sum += w * std::cos(th) * std::sin(th) * (b - a) / nodes;
            }
            return sum;
        };
        double m = 0;
        if (j > 0) m += part((j - 1) * dt, j * dt, true);
        if (j < theta_intervals) m += part(j * dt, (j + 1) * dt, false);
        return m * dp;
    };
    t.values.resize(mass.size());
    for (int j = 0; j < rows; ++j) {
        const double measure = hat_measure(j);
        if (j == 0) { // one point: the row shares its mass
            double total = 0;
            for (int k = 0; k < phi_count; ++k) total += mass[k];
            for (int k = 0; k < phi_count; ++k) t.values[k] = total / (measure * phi_count);
            continue;
        }
        for (int k = 0; k < phi_count; ++k)
            t.values[size_t(j) * phi_count + k] =
                measure > 0 ? mass[size_t(j) * phi_count + k] / measure : 0.0;
    }
    return t;
}

} // namespace gonio
