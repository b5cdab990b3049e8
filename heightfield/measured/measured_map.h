#pragma once
// Measured height maps as instruments write them, before preparation (map_preparation.h): a
// rectangular grid of heights with its lateral spacing, missing points as NaN. Each file format
// is a reader in its own file (x3p_reader.cpp, sdf_reader.cpp, gsf_reader.cpp, matrix_reader.cpp,
// and gonio's own OpenEXR maps), listed once in measured_formats(); a file's format is chosen by
// its content (magic bytes), then by its extension.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace gonio {

// The one length unit of third-party maps once read: heights and spacings in micrometres.
inline constexpr const char* kMeasuredUnit = "um";

struct MeasuredMap {
    int nx = 0, ny = 0;     // columns (x) and rows (y)
    double dx = 0, dy = 0;  // spacing between samples along x and y
    std::vector<double> z;  // row-major z[y * nx + x]; NaN where the instrument gave no point
    std::string format;     // the reader's name
    std::string unit;       // kMeasuredUnit, or "" for gonio's unitless maps
    std::string note;       // what the reader found (data type, the file's own units)
    bool gonio_map = false; // written by gonio (EXR with its attributes): periodic already

    double& at(int x, int y) { return z[size_t(y) * nx + x]; }
    double at(int x, int y) const { return z[size_t(y) * nx + x]; }
};

// What a reader needs besides the file: a plain matrix has no spacing of its own.
struct MeasuredReadOptions {
    double matrix_spacing = 0;      // surface.input_spacing, in matrix_unit; 0 when not given
    std::string matrix_unit = "um"; // surface.input_unit: a plain matrix's length unit
    bool verify_checksums = true;   // surface.input_checksums: refuse files whose checksums fail
};

struct MeasuredFormat {
    const char* name;
    const char* summary;
    std::vector<std::string> extensions; // lower case, with the dot
    // Whether the file's first bytes are this format's.
    bool (*recognises)(const std::string& head);
    // Throws std::runtime_error naming the file and what is wrong.
    MeasuredMap (*read)(const std::string& path, const MeasuredReadOptions& options);
};

const std::vector<const MeasuredFormat*>& measured_formats();
const MeasuredFormat& x3p_format();
const MeasuredFormat& sdf_format();
const MeasuredFormat& gsf_format();
const MeasuredFormat& matrix_format();
const MeasuredFormat& exr_map_format();

// The format of `path`: by content, then by extension; throws std::runtime_error naming the file
// and the formats when none fits.
const MeasuredFormat& measured_format_of(const std::string& path);
MeasuredMap read_measured_map(const std::string& path, const MeasuredReadOptions& options = {});

// Helpers the readers share. The whole file (throws naming it when unreadable).
std::string read_file_bytes(const std::string& path);
// Text from a file, fit to quote in a message: quoted, control and non-ASCII bytes as '?', at
// most 40 characters.
std::string quoted(const std::string& text);
// "name = value" lines (the SDF and GSF headers): names and values trimmed.
std::map<std::string, std::string> header_fields(const std::string& text);
// A header field as a finite number: `fallback` when absent, else an error naming the file.
double header_number(const std::map<std::string, std::string>& fields, const std::string& name,
                     const std::string& path, const char* format,
                     std::optional<double> fallback = std::nullopt);
// The length units a file may state (m, mm, um or µm, nm) and micrometres per unit; 0 for any
// other.
double micrometres_per(const std::string& unit);
inline const char* const kLengthUnits = "m, mm, um (or µm), nm";

// A map's size and spacing checked (positive, finite, at most 2^15 per side) and z sized.
void check_map_shape(MeasuredMap& m, const std::string& path);

} // namespace gonio
