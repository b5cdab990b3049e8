#include "gonio/material/ior_table.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace gonio {

IorTable IorTable::load(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open refractive-index table");
    IorTable t;
    t.path_ = path;
    std::string line;
    int line_no = 0;
    bool header_seen = false;
    while (std::getline(in, line)) {
        ++line_no;
        if (line.empty() || line[0] == '#') {
            if (!line.empty()) t.source_ += line.substr(1) + "\n";
            continue;
        }
        if (!header_seen && line.find_first_of("abcdefghijklmnopqrstuvwxyz") != std::string::npos) {
            header_seen = true;
            continue;
        }
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream row(line);
        double w, n, k;
        if (!(row >> w >> n >> k) || !(w > 0) || !(n > 0) || !(k >= 0) || !std::isfinite(w) ||
            !std::isfinite(n) || !std::isfinite(k))
            throw std::runtime_error(path + ":" + std::to_string(line_no) +
                                     ": expected 'wavelength_nm,n,k', finite, with wavelength > "
                                     "0, n > 0, k >= 0");
        if (!t.wavelength_.empty() && w <= t.wavelength_.back())
            throw std::runtime_error(path + ":" + std::to_string(line_no) +
                                     ": wavelengths must increase");
        t.wavelength_.push_back(w);
        t.n_.push_back(n);
        t.k_.push_back(k);
    }
    if (t.wavelength_.size() < 2)
        throw std::runtime_error(path + ": a refractive-index table needs at least two rows");
    return t;
}

std::complex<double> IorTable::at(double w) const {
    if (!(w >= min_wavelength() && w <= max_wavelength()))
        throw std::out_of_range("wavelength " + std::to_string(w) + " nm is outside " + path_ +
                                " [" + std::to_string(min_wavelength()) + ", " +
                                std::to_string(max_wavelength()) + "] nm");
    const auto it = std::upper_bound(wavelength_.begin(), wavelength_.end(), w);
    const size_t hi = std::min<size_t>(it - wavelength_.begin(), wavelength_.size() - 1);
    const size_t lo = hi - 1;
    const double t = (w - wavelength_[lo]) / (wavelength_[hi] - wavelength_[lo]);
    return {n_[lo] + t * (n_[hi] - n_[lo]), k_[lo] + t * (k_[hi] - k_[lo])};
}

std::string data_directory() {
    if (const char* env = std::getenv("GONIO_DATA_DIR")) return env;
    return std::string(GONIO_SOURCE_DIR) + "/data";
}

std::string resolve_ior_path(const std::string& name) {
    const bool is_path = name.find('/') != std::string::npos ||
                         (name.size() > 4 && name.compare(name.size() - 4, 4, ".csv") == 0);
    return is_path ? name : data_directory() + "/ior/" + name + ".csv";
}

} // namespace gonio
