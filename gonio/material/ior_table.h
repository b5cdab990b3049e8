#pragma once
// A tabulated complex refractive index n + i k against wavelength (data/ior/*.csv).
#include <complex>
#include <string>
#include <vector>

namespace gonio {

class IorTable {
  public:
    // Reads "wavelength_nm,n,k" rows ('#' comments and one header line allowed). Throws
    // std::runtime_error naming the file (and line) on a missing or malformed file.
    static IorTable load(const std::string& path);

    // Linear interpolation; throws std::out_of_range outside [min_wavelength, max_wavelength].
    std::complex<double> at(double wavelength_nm) const;
    double min_wavelength() const { return wavelength_.front(); }
    double max_wavelength() const { return wavelength_.back(); }
    const std::string& path() const { return path_; }
    // Comment lines of the file (its source).
    const std::string& source() const { return source_; }

  private:
    std::string path_, source_;
    std::vector<double> wavelength_, n_, k_;
};

// Path of a named table ("Au" -> <data dir>/ior/Au.csv), or the name itself if it is a path.
// The data directory is $GONIO_DATA_DIR if set, else the source tree's data/.
std::string resolve_ior_path(const std::string& name_or_path);
std::string data_directory();

} // namespace gonio
