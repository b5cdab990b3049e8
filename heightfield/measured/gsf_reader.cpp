// Gwyddion Simple Field (GSF, gwyddion.net/documentation/user-guide-en/gsf.html): the line
// "Gwyddion Simple Field 1.0", "name = value" lines (XRes, YRes required; XReal, YReal the
// physical size; XYUnits, ZUnits), 1-4 NUL bytes aligning the data to 4, then XRes x YRes
// little-endian float32, row by row. Missing points are NaN.
#include "heightfield/measured/measured_map.h"

#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {
const std::string kMagic = "Gwyddion Simple Field 1.0\n";

// Micrometres per unit of a GSF length unit (SI base units, as Gwyddion writes them; none is m).
double gsf_micrometres_per(const std::string& unit, const std::string& path, const char* key) {
    if (const double um = micrometres_per(unit.empty() ? "m" : unit); um > 0) return um;
    throw std::runtime_error(path + ": GSF " + std::string(key) + " " + quoted(unit) +
                             " is not a length (allowed: " + kLengthUnits + ")");
}

MeasuredMap read_gsf(const std::string& path, const MeasuredReadOptions&) {
    const std::string bytes = read_file_bytes(path);
    if (bytes.compare(0, kMagic.size(), kMagic) != 0)
        throw std::runtime_error(path + ": a GSF file starts with 'Gwyddion Simple Field 1.0'");
    const size_t nul = bytes.find('\0', kMagic.size());
    if (nul == std::string::npos)
        throw std::runtime_error(path + ": the GSF header is not terminated by NUL bytes");
    auto fields = header_fields(bytes.substr(kMagic.size(), nul - kMagic.size()));
    auto number = [&](const char* name, std::optional<double> fallback) {
        return header_number(fields, name, path, "GSF", fallback);
    };
    MeasuredMap m;
    const double xres = number("XRes", {}), yres = number("YRes", {});
    m.nx = int(std::min(std::max(xres, 0.0), 1e9));
    m.ny = int(std::min(std::max(yres, 0.0), 1e9));
    const double lateral = gsf_micrometres_per(fields["XYUnits"], path, "XYUnits");
    const double vertical = gsf_micrometres_per(fields["ZUnits"], path, "ZUnits");
    m.dx = m.nx > 0 ? number("XReal", 1.0) / m.nx * lateral : 0;
    m.dy = m.ny > 0 ? number("YReal", 1.0) / m.ny * lateral : 0;
    check_map_shape(m, path);
    const size_t data = (nul / 4 + 1) * 4; // the padding aligns the data to 4 bytes
    for (size_t k = nul; k < data; ++k)
        if (k >= bytes.size() || bytes[k] != '\0')
            throw std::runtime_error(path + ": the GSF header's NUL padding is malformed");
    if (bytes.size() - data < m.z.size() * 4)
        throw std::runtime_error(path + ": " + std::to_string(bytes.size() - data) +
                                 " bytes of data; " + std::to_string(m.nx) + " x " +
                                 std::to_string(m.ny) + " floats need " +
                                 std::to_string(m.z.size() * 4) + " (truncated?)");
    for (size_t k = 0; k < m.z.size(); ++k) {
        float v;
        std::memcpy(&v, bytes.data() + data + 4 * k, 4);
        m.z[k] = std::isfinite(v) ? double(v) * vertical : NAN;
    }
    m.unit = kMeasuredUnit;
    m.note = "GSF, XYUnits " + quoted(fields["XYUnits"]) + ", ZUnits " + quoted(fields["ZUnits"]) +
             " read as micrometres";
    return m;
}

bool gsf_recognises(const std::string& head) {
    return head.compare(0, kMagic.size(), kMagic) == 0;
}
} // namespace

const MeasuredFormat& gsf_format() {
    static const MeasuredFormat f{
        "gsf", "Gwyddion Simple Field", {".gsf"}, &gsf_recognises, &read_gsf};
    return f;
}

} // namespace gonio
