// A plain matrix of heights: one row of the map (constant y) per line, values separated by
// whitespace, commas or semicolons; '#' starts a comment; nan, NaN or an empty CSV field is a
// missing point. It has no spacing or unit of its own: surface.input_spacing gives the spacing,
// surface.input_unit the unit of both (micrometres unless set).
#include "heightfield/measured/measured_map.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {
MeasuredMap read_matrix(const std::string& path, const MeasuredReadOptions& options) {
    if (!(options.matrix_spacing > 0))
        throw std::runtime_error(path + ": a plain matrix of heights has no spacing: set "
                                        "surface.input_spacing (in surface.input_unit)");
    const double um = micrometres_per(options.matrix_unit);
    if (!(um > 0))
        throw std::runtime_error(path + ": surface.input_unit " + quoted(options.matrix_unit) +
                                 " is not a length unit (allowed: " + kLengthUnits + ")");
    const std::string bytes = read_file_bytes(path);
    std::vector<double> values;
    int columns = -1, rows = 0, line_number = 0;
    std::istringstream in(bytes);
    for (std::string line; std::getline(in, line);) {
        ++line_number;
        if (const size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const bool separated = line.find_first_of(",;") != std::string::npos;
        int count = 0;
        size_t at = 0;
        while (at <= line.size()) {
            size_t end = separated ? line.find_first_of(",;", at) : line.find_first_of(" \t\r", at);
            if (end == std::string::npos) end = line.size();
            std::string token = line.substr(at, end - at);
            token.erase(0, token.find_first_not_of(" \t\r"));
            token.erase(token.find_last_not_of(" \t\r") + 1);
            at = end + 1;
            if (token.empty() && !separated) continue;
            double v = NAN;
            if (!token.empty() && token != "nan" && token != "NaN" && token != "NAN") {
                char* stop = nullptr;
                v = std::strtod(token.c_str(), &stop);
                if (*stop != '\0' || !std::isfinite(v))
                    throw std::runtime_error(path + ":" + std::to_string(line_number) + ": " +
                                             quoted(token) + " is not a height");
            }
            values.push_back(v);
            ++count;
        }
        if (columns >= 0 && count != columns)
            throw std::runtime_error(path + ":" + std::to_string(line_number) + ": " +
                                     std::to_string(count) + " values; the rows above have " +
                                     std::to_string(columns));
        columns = count;
        ++rows;
    }
    MeasuredMap m;
    m.nx = std::max(columns, 0);
    m.ny = rows;
    m.dx = m.dy = options.matrix_spacing * um;
    check_map_shape(m, path);
    m.z = std::move(values);
    if (um != 1)
        for (double& z : m.z) z *= um;
    m.unit = kMeasuredUnit;
    m.note = "plain matrix, heights and surface.input_spacing in " + options.matrix_unit;
    return m;
}
} // namespace

const MeasuredFormat& matrix_format() {
    static const MeasuredFormat f{"matrix",
                                  "plain matrix of heights (whitespace or CSV), spacing from "
                                  "surface.input_spacing",
                                  {".txt", ".csv", ".asc", ".dat"},
                                  nullptr,
                                  &read_matrix};
    return f;
}

} // namespace gonio
