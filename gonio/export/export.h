#pragma once
// `gonio export`: a simulated case handed on in the formats other tools read (one file per
// format in this folder, each with its refusal rules):
//   rgl    - the tensor file of Dupuy & Jakob 2018 (Mitsuba 3 / pbrt-v4 `measured`)
//   merl   - MERL .binary (isotropic reflection, sRGB)
//   astm   - ASTM E1392 text, one row per incidence and cell centre
//   albedo - directional albedo per order, E(theta_i), as CSV (multiple-scattering compensation)
// Every export writes to a temporary name renamed when complete, and refuses what its format
// cannot hold with ExportRefused and a one-line reason.
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

struct ExportRefused : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct ExportOptions {
    std::string input;  // the result file
    std::string format; // rgl | merl | astm | albedo
    std::string output;
    std::string case_name;       // empty: the file's only case
    std::string orders = "linf"; // l1 | l2plus | linf (rgl, merl, astm)
    bool rgb = false;            // rgl: an `rgb` field instead of `spectra`
    std::string sweep;           // albedo: a config key that varies across the file's cases
    bool overwrite = false;
    bool quiet = false;
};

struct ExportReport {
    std::string output;
    long long bytes = 0;
    double seconds = 0;
    std::vector<std::string> notes; // what the export did that a user should know
};

const std::vector<std::string>& export_formats();
// Throws ExportRefused (what the format cannot hold) or std::runtime_error (unreadable input).
ExportReport export_result(const ExportOptions& options);

} // namespace gonio
