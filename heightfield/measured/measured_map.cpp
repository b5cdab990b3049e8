#include "heightfield/measured/measured_map.h"

#include "heightfield/exr_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace gonio {

double micrometres_per(const std::string& unit) {
    if (unit == "m") return 1e6;
    if (unit == "mm") return 1e3;
    if (unit == "um" || unit == "µm" || unit == "μm") return 1; // micro sign or Greek mu
    if (unit == "nm") return 1e-3;
    return 0;
}

const std::vector<const MeasuredFormat*>& measured_formats() {
    // Content first: the formats with magic bytes before the plain matrix, which has none.
    static const std::vector<const MeasuredFormat*> all = {
        &exr_map_format(), &x3p_format(), &sdf_format(), &gsf_format(), &matrix_format()};
    return all;
}

std::string read_file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open the height map");
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw std::runtime_error(path + ": read error");
    return bytes;
}

std::string quoted(const std::string& text) {
    std::string out = "'";
    for (size_t k = 0; k < text.size() && k < 40; ++k) {
        const unsigned char c = static_cast<unsigned char>(text[k]);
        out += c >= 32 && c < 127 ? char(c) : '?';
    }
    return out + (text.size() > 40 ? "...'" : "'");
}

std::map<std::string, std::string> header_fields(const std::string& text) {
    auto trim = [](std::string s) {
        s.erase(0, s.find_first_not_of(" \t\r"));
        s.erase(s.find_last_not_of(" \t\r") + 1);
        return s;
    };
    std::map<std::string, std::string> fields;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (const size_t eq = line.find('='); eq != std::string::npos)
            fields[trim(line.substr(0, eq))] = trim(line.substr(eq + 1));
    return fields;
}

double header_number(const std::map<std::string, std::string>& fields, const std::string& name,
                     const std::string& path, const char* format, std::optional<double> fallback) {
    const auto it = fields.find(name);
    if (it == fields.end()) {
        if (fallback) return *fallback;
        throw std::runtime_error(path + ": the " + format + " header has no " + name);
    }
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (end == it->second.c_str() || !std::isfinite(v))
        throw std::runtime_error(path + ": " + format + " " + name + " is not a number (" +
                                 quoted(it->second) + ")");
    return v;
}

void check_map_shape(MeasuredMap& m, const std::string& path) {
    constexpr int kMaxSide = 1 << 15;
    if (m.nx < 2 || m.ny < 2 || m.nx > kMaxSide || m.ny > kMaxSide)
        throw std::runtime_error(path + ": a map of " + std::to_string(m.nx) + " x " +
                                 std::to_string(m.ny) + " points (allowed: 2 to " +
                                 std::to_string(kMaxSide) + " per side)");
    // At most 2^28 points (a 16384^2 map): a header cannot make gonio allocate more.
    if (double(m.nx) * m.ny > double(1 << 28))
        throw std::runtime_error(path + ": " + std::to_string(m.nx) + " x " + std::to_string(m.ny) +
                                 " points (at most 2^28 are read)");
    for (double d : {m.dx, m.dy})
        if (!(d > 0) || !std::isfinite(d))
            throw std::runtime_error(path + ": the lateral spacing must be finite and > 0");
    m.z.assign(size_t(m.nx) * m.ny, 0.0);
}

const MeasuredFormat& measured_format_of(const std::string& path) {
    if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no such height map");
    std::string head(64, '\0');
    {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw std::runtime_error(path + ": cannot open the height map");
        in.read(head.data(), std::streamsize(head.size()));
        head.resize(size_t(in.gcount()));
    }
    for (const MeasuredFormat* f : measured_formats())
        if (f->recognises && f->recognises(head)) return *f;
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    for (const MeasuredFormat* f : measured_formats())
        if (std::find(f->extensions.begin(), f->extensions.end(), ext) != f->extensions.end())
            return *f;
    std::string names;
    for (const MeasuredFormat* f : measured_formats())
        names += std::string(names.empty() ? "" : ", ") + f->name;
    throw std::runtime_error(path + ": not a height map gonio reads (formats: " + names + ")");
}

MeasuredMap read_measured_map(const std::string& path, const MeasuredReadOptions& options) {
    const MeasuredFormat& f = measured_format_of(path);
    MeasuredMap m = f.read(path, options);
    m.format = f.name;
    return m;
}

// gonio's own maps and any square single-channel OpenEXR (exr_io.h), unitless.
namespace {
bool exr_recognises(const std::string& head) {
    return head.size() >= 4 && head.compare(0, 4, "\x76\x2f\x31\x01") == 0;
}
MeasuredMap read_exr(const std::string& path, const MeasuredReadOptions&) {
    ExrAttributes attrs;
    const HeightField s = read_height_exr(path, &attrs);
    MeasuredMap m;
    m.nx = m.ny = s.n;
    m.dx = m.dy = s.spacing;
    m.z.assign(s.h.begin(), s.h.end());
    for (const auto& [k, v] : attrs.text) m.gonio_map = m.gonio_map || k.rfind("gonio_", 0) == 0;
    m.note = m.gonio_map ? "written by gonio" : "OpenEXR height map";
    return m;
}
} // namespace

const MeasuredFormat& exr_map_format() {
    static const MeasuredFormat f{"exr",
                                  "OpenEXR height map (gonio's own; square, channel Y)",
                                  {".exr"},
                                  &exr_recognises,
                                  &read_exr};
    return f;
}

} // namespace gonio
