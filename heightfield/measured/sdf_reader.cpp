// ISO 25178-71 surface data files (SDF), ASCII ("aISO-1.0") and binary ("bISO-1.0"): a header of
// NumPoints (x), NumProfiles (y), the X, Y and Z scales (metres per unit), the data type, then the
// points profile by profile. Missing points: BAD in ASCII files; the type's most negative value
// (integers) or NaN (doubles) in binary ones.
#include "heightfield/measured/measured_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {
constexpr double kMetresToUnit = 1e6; // kMeasuredUnit: micrometres

struct SdfHeader {
    long long points = 0, profiles = 0;
    double xscale = 0, yscale = 0, zscale = 0;
    int data_type = 0, compression = 0;
};

// Data types (ISO 25178-71): 5 int16, 6 int32, 7 double.
size_t width_of(int type, const std::string& path) {
    if (type == 5) return 2;
    if (type == 6) return 4;
    if (type == 7) return 8;
    throw std::runtime_error(path + ": SDF data type " + std::to_string(type) +
                             " (allowed: 5 int16, 6 int32, 7 double)");
}

MeasuredMap shaped(const SdfHeader& h, const std::string& path) {
    if (h.compression != 0)
        throw std::runtime_error(path + ": compressed SDF data (Compression " +
                                 std::to_string(h.compression) + ") is not read");
    MeasuredMap m;
    m.nx = int(std::min<long long>(h.points, 1 << 30));
    m.ny = int(std::min<long long>(h.profiles, 1 << 30));
    m.dx = h.xscale * kMetresToUnit;
    m.dy = h.yscale * kMetresToUnit;
    check_map_shape(m, path);
    if (!(std::abs(h.zscale) > 0) || !std::isfinite(h.zscale))
        throw std::runtime_error(path + ": Zscale must be finite and not 0");
    m.unit = kMeasuredUnit;
    return m;
}

MeasuredMap read_ascii(const std::string& path, const std::string& bytes) {
    // Sections separated by '*': header, data, optional trailer.
    const size_t header_end = bytes.find('*');
    if (header_end == std::string::npos)
        throw std::runtime_error(path + ": an SDF header ends with '*'; none found");
    const auto fields = header_fields(bytes.substr(8, header_end - 8));
    auto field = [&](const char* name) { return header_number(fields, name, path, "SDF"); };
    // Counts clamped, so that an absurd value cannot overflow a conversion: it is refused below.
    auto count = [&](const char* name) { return std::clamp(field(name), -1.0, 1e9); };
    SdfHeader h;
    h.points = (long long)count("NumPoints");
    h.profiles = (long long)count("NumProfiles");
    h.xscale = field("Xscale"), h.yscale = field("Yscale"), h.zscale = field("Zscale");
    h.data_type = int(count("DataType"));
    h.compression =
        int(std::clamp(header_number(fields, "Compression", path, "SDF", 0.0), -1.0, 1e9));
    width_of(h.data_type, path); // a known type, though ASCII values are read as numbers
    MeasuredMap m = shaped(h, path);
    const size_t data_end = bytes.find('*', header_end + 1);
    std::istringstream data(bytes.substr(header_end + 1, data_end == std::string::npos
                                                             ? std::string::npos
                                                             : data_end - header_end - 1));
    size_t k = 0;
    for (std::string token; data >> token; ++k) {
        if (k >= m.z.size())
            throw std::runtime_error(path + ": more than NumPoints x NumProfiles = " +
                                     std::to_string(m.z.size()) + " values");
        if (token == "BAD") {
            m.z[k] = NAN;
            continue;
        }
        char* end = nullptr;
        const double v = std::strtod(token.c_str(), &end);
        if (*end != '\0' || !std::isfinite(v))
            throw std::runtime_error(path + ": value " + std::to_string(k + 1) + " (" +
                                     quoted(token) + ") is not a number");
        m.z[k] = v * h.zscale * kMetresToUnit;
    }
    if (k != m.z.size())
        throw std::runtime_error(path + ": " + std::to_string(k) + " values; NumPoints x " +
                                 "NumProfiles = " + std::to_string(m.z.size()) +
                                 " needed (truncated?)");
    m.note = "SDF (ASCII), lengths in metres read as micrometres";
    return m;
}

template <class T>
T field_at(const std::string& bytes, size_t offset) {
    T v;
    std::memcpy(&v, bytes.data() + offset, sizeof v); // little-endian, as the standard's
    return v;
}

MeasuredMap read_binary(const std::string& path, const std::string& bytes) {
    // After the magic: ManufacID[10], CreateDate[12], ModDate[12], NumPoints u16, NumProfiles u16,
    // Xscale, Yscale, Zscale, Zresolution (doubles), Compression, DataType, CheckType (bytes).
    constexpr size_t kHeader = 8 + 10 + 12 + 12 + 2 + 2 + 4 * 8 + 3;
    if (bytes.size() < kHeader)
        throw std::runtime_error(path + ": shorter than a binary SDF header (" +
                                 std::to_string(kHeader) + " bytes)");
    SdfHeader h;
    h.points = field_at<std::uint16_t>(bytes, 42);
    h.profiles = field_at<std::uint16_t>(bytes, 44);
    h.xscale = field_at<double>(bytes, 46);
    h.yscale = field_at<double>(bytes, 54);
    h.zscale = field_at<double>(bytes, 62);
    h.compression = static_cast<unsigned char>(bytes[78]);
    h.data_type = static_cast<unsigned char>(bytes[79]);
    const size_t width = width_of(h.data_type, path);
    MeasuredMap m = shaped(h, path);
    if (bytes.size() < kHeader + m.z.size() * width)
        throw std::runtime_error(path + ": " + std::to_string(bytes.size() - kHeader) +
                                 " bytes of points; " + std::to_string(m.nx) + " x " +
                                 std::to_string(m.ny) + " need " +
                                 std::to_string(m.z.size() * width) + " (truncated?)");
    for (size_t k = 0; k < m.z.size(); ++k) {
        const size_t at = kHeader + k * width;
        double v;
        if (width == 2) {
            const auto i = field_at<std::int16_t>(bytes, at);
            v = i == INT16_MIN ? NAN : double(i);
        } else if (width == 4) {
            const auto i = field_at<std::int32_t>(bytes, at);
            v = i == INT32_MIN ? NAN : double(i);
        } else {
            v = field_at<double>(bytes, at);
        }
        m.z[k] = std::isfinite(v) ? v * h.zscale * kMetresToUnit : NAN;
    }
    m.note = "SDF (binary, data type " + std::to_string(h.data_type) +
             "), lengths in metres read as micrometres";
    return m;
}

bool sdf_recognises(const std::string& head) {
    return head.size() >= 8 &&
           (head.compare(0, 8, "aISO-1.0") == 0 || head.compare(0, 8, "bISO-1.0") == 0);
}

MeasuredMap read_sdf(const std::string& path, const MeasuredReadOptions&) {
    const std::string bytes = read_file_bytes(path);
    if (!sdf_recognises(bytes))
        throw std::runtime_error(path + ": an SDF file starts with aISO-1.0 or bISO-1.0");
    return bytes[0] == 'a' ? read_ascii(path, bytes) : read_binary(path, bytes);
}
} // namespace

const MeasuredFormat& sdf_format() {
    static const MeasuredFormat f{"sdf",
                                  "ISO 25178-71 surface data file, ASCII or binary",
                                  {".sdf"},
                                  &sdf_recognises,
                                  &read_sdf};
    return f;
}

} // namespace gonio
