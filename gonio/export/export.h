#pragma once
// `gonio export`: a simulated case handed on in the formats other tools read (one file per
// format in this folder, each with its refusal rules):
//   rgl    - the tensor file of Dupuy & Jakob 2018 (Mitsuba 3 / pbrt-v4 `measured`)
//   merl   - MERL .binary (isotropic reflection, sRGB)
//   astm   - ASTM E1392 text, one row per incidence and cell centre
//   albedo - directional albedo per order, E(theta_i), as CSV (multiple-scattering compensation)
// Every export writes to a temporary name renamed when complete, and refuses what its format
// cannot hold with ExportRefused and a one-line reason.
#include "gonio/table/bsdf_table.h"

#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

struct ExportRefused : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct ExportFormat;
struct ResultCase;

struct ExportOptions {
    std::string input; // the result file
    const ExportFormat* format = nullptr;
    std::string output;
    std::string case_name;                // empty: the file's only case
    TableOrder orders = TableOrder::linf; // the order written (rgl, merl, astm)
    bool rgb = false;                     // rgl: an `rgb` field instead of `spectra`
    std::string sweep; // albedo: a config key that varies across the file's cases
    bool overwrite = false;
    bool quiet = false;
};

struct ExportReport {
    std::string output;
    long long bytes = 0;
    double seconds = 0;
    std::vector<std::string> notes; // what the export did that a user should know
};

// An export format, declared in its own file (rgl_export.cpp, ...) and listed once in
// export_formats(): the command line's choices and help come from these.
struct ExportFormat {
    const char* name;
    const char* summary;
    bool binary;       // written in binary mode
    bool rgb_option;   // takes --rgb
    bool sweep_option; // takes --sweep
    // Writes the case to `out` and adds what the user should know to `report.notes`; throws
    // ExportRefused with the one-line reason when the case cannot be represented.
    void (*write)(const ResultCase& c, const ExportOptions& o, std::ostream& out,
                  ExportReport& report);
};

const std::vector<const ExportFormat*>& export_formats();
// Throws std::invalid_argument naming the formats.
const ExportFormat& export_format_named(const std::string& name);
const ExportFormat& rgl_format();
const ExportFormat& merl_format();
const ExportFormat& astm_format();
const ExportFormat& albedo_format();

// Throws std::invalid_argument for options that do not go together (no format or output, the
// output the input, --rgb or --sweep with a format without them).
void check_export_options(const ExportOptions& options);
// Throws ExportRefused (what the format cannot hold), std::invalid_argument (the options, as
// above) or std::runtime_error (an unreadable or corrupt input, naming it).
ExportReport export_result(const ExportOptions& options);

} // namespace gonio
