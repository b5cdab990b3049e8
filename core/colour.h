#pragma once
// Colour science for the exporters (and the renderer): CIE 1931 2-degree colour matching functions
// and illuminant D65 (tables in data/cie, CIE 15:2004), a channel spectrum to CIE XYZ, and XYZ to
// linear sRGB (IEC 61966-2-1).
#include <array>
#include <string>
#include <vector>

namespace gonio {

struct ColourTables {
    std::vector<double> wavelength_nm, x_bar, y_bar, z_bar, d65; // 5 nm steps, 380-780 nm
};
// Reads data_dir/cie/cie1931_2deg.csv and data_dir/cie/d65.csv; throws std::runtime_error naming
// the file.
ColourTables load_colour_tables(const std::string& data_dir);

using Matrix3xN = std::vector<std::array<double, 3>>; // one column (X, Y, Z or R, G, B) per channel

// The linear map from channel values at `wavelengths_nm` (the spectrum between them linear,
// constant beyond the ends) to the XYZ of that reflectance spectrum under D65, normalised so that
// a perfect white reflector has Y = 1.
Matrix3xN spectrum_to_xyz_matrix(const ColourTables& t, const std::vector<double>& wavelengths_nm);
// The same to linear sRGB: a white reflector maps to (1, 1, 1) up to the tables' rounding.
Matrix3xN spectrum_to_linear_srgb_matrix(const ColourTables& t,
                                         const std::vector<double>& wavelengths_nm);
std::array<double, 3> xyz_to_linear_srgb(const std::array<double, 3>& xyz);
std::array<double, 3> linear_srgb_to_xyz(const std::array<double, 3>& rgb);
// CIE 1976 L*a*b* of XYZ against the D65 white (Y = 1) [CIE 15:2004 section 8.2.1].
std::array<double, 3> xyz_to_lab(const std::array<double, 3>& xyz);
// The sRGB transfer function (IEC 61966-2-1): linear [0, 1] to encoded [0, 1].
double srgb_encode(double linear);
// CIEDE2000 colour difference with kL = kC = kH = 1 [Sharma, Wu & Dalal 2005, Eqs. 1-21].
double ciede2000(const std::array<double, 3>& lab1, const std::array<double, 3>& lab2);
std::array<double, 3> map_channels(const Matrix3xN& m, const double* channels);

} // namespace gonio
