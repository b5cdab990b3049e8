// ISO 25178-72 / ISO 5436-2 XML (X3P): a zip holding main.xml (axes, increments, data type, the
// point data's MD5) and the binary point data, little-endian, x fastest; md5checksum.hex holds
// main.xml's MD5. Lengths are metres. Missing points: NaN for float data, or the points cleared
// in the optional bit array of valid points (ValidPointsLink).
#include "heightfield/measured/measured_map.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <openssl/evp.h>
#include <pugixml.hpp>
#include <stdexcept>
#include <zip.h>

namespace gonio {

namespace {
constexpr double kMetresToUnit = 1e6; // kMeasuredUnit: micrometres

std::string md5_hex(const std::string& bytes) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (!EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_md5(), nullptr))
        throw std::runtime_error("MD5 failed");
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (unsigned k = 0; k < size; ++k) out += hex[digest[k] >> 4], out += hex[digest[k] & 15];
    return out;
}

std::string lower_trimmed(std::string s) {
    s.erase(0, s.find_first_not_of(" \t\r\n"));
    s.erase(s.find_last_not_of(" \t\r\n") + 1);
    for (char& c : s) c = char(std::tolower((unsigned char)c));
    return s;
}

class Archive {
  public:
    explicit Archive(const std::string& path) : path_(path) {
        int error = 0;
        zip_ = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &error);
        if (!zip_) {
            zip_error_t e;
            zip_error_init_with_code(&e, error);
            const std::string why = zip_error_strerror(&e);
            zip_error_fini(&e);
            throw std::runtime_error(path + ": not a readable X3P (zip) archive: " + why);
        }
    }
    ~Archive() { zip_discard(zip_); }
    Archive(const Archive&) = delete;
    Archive& operator=(const Archive&) = delete;

    // The entry whose name ends with `suffix` (X3P writers may put everything in a folder).
    std::string find(const std::string& suffix) const {
        const zip_int64_t count = zip_get_num_entries(zip_, 0);
        for (zip_int64_t k = 0; k < count; ++k) {
            const std::string name = zip_get_name(zip_, zip_uint64_t(k), 0);
            if (name == suffix ||
                (name.size() > suffix.size() &&
                 name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
                 name[name.size() - suffix.size() - 1] == '/'))
                return name;
        }
        return "";
    }
    std::string read(const std::string& name, zip_uint64_t limit) const {
        zip_stat_t st;
        if (zip_stat(zip_, name.c_str(), 0, &st) != 0)
            throw std::runtime_error(path_ + ": the archive has no " + quoted(name));
        if (st.size > limit)
            throw std::runtime_error(path_ + ": " + quoted(name) + " is larger than expected (" +
                                     std::to_string(st.size) + " bytes)");
        std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> f(zip_fopen(zip_, name.c_str(), 0),
                                                            &zip_fclose);
        if (!f)
            throw std::runtime_error(path_ + ": cannot open " + quoted(name) + " in the archive");
        std::string bytes(size_t(st.size), '\0');
        if (zip_fread(f.get(), bytes.data(), st.size) != zip_int64_t(st.size))
            throw std::runtime_error(path_ + ": " + quoted(name) + " is truncated or corrupt");
        return bytes;
    }

  private:
    std::string path_;
    zip_t* zip_ = nullptr;
};

double number(const pugi::xml_node& node, const char* child, const std::string& path,
              bool required = true, double fallback = 0) {
    const pugi::xml_node c = node.child(child);
    const std::string text = c.text().as_string();
    if (text.empty()) {
        if (required)
            throw std::runtime_error(path + ": main.xml has no " + std::string(node.name()) + "/" +
                                     child);
        return fallback;
    }
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || !std::isfinite(v))
        throw std::runtime_error(path + ": main.xml's " + std::string(node.name()) + "/" + child +
                                 " is not a number (" + quoted(text) + ")");
    return v;
}

template <class T>
T little_endian(const char* p) {
    T v;
    std::memcpy(&v, p, sizeof v); // the machines gonio runs on are little-endian, as X3P is
    return v;
}

MeasuredMap read_x3p(const std::string& path, const MeasuredReadOptions& options) {
    const Archive zip(path);
    const std::string main_name = zip.find("main.xml");
    if (main_name.empty()) throw std::runtime_error(path + ": an X3P archive needs main.xml");
    const std::string folder = main_name.substr(0, main_name.size() - 8);
    const std::string xml = zip.read(main_name, 1 << 24);
    // md5checksum.hex: main.xml's MD5 (ISO 5436-2), when present.
    const std::string sum_name = zip.find("md5checksum.hex");
    if (options.verify_checksums && !sum_name.empty()) {
        const std::string expected = lower_trimmed(zip.read(sum_name, 4096)).substr(0, 32);
        if (expected != md5_hex(xml))
            throw std::runtime_error(path + ": main.xml does not match its MD5 checksum "
                                            "(md5checksum.hex): the file is damaged or was "
                                            "edited (surface.input_checksums = false reads it)");
    }
    pugi::xml_document doc;
    if (const pugi::xml_parse_result r = doc.load_buffer(xml.data(), xml.size()); !r)
        throw std::runtime_error(path + ": main.xml is not XML (" + r.description() + ")");
    const pugi::xml_node root = doc.document_element();
    const pugi::xml_node r1 = root.child("Record1"), r3 = root.child("Record3");
    if (!r1 || !r3) throw std::runtime_error(path + ": main.xml needs Record1 and Record3");
    const std::string feature = r1.child("FeatureType").text().as_string();
    if (feature != "SUR")
        throw std::runtime_error(path + ": feature type " + quoted(feature) +
                                 " (gonio reads areal surfaces, SUR)");
    const pugi::xml_node axes = r1.child("Axes");
    const pugi::xml_node cx = axes.child("CX"), cy = axes.child("CY"), cz = axes.child("CZ");
    if (!cx || !cy || !cz) throw std::runtime_error(path + ": main.xml needs axes CX, CY, CZ");
    for (const pugi::xml_node& a : {cx, cy})
        if (std::string(a.child("AxisType").text().as_string()) != "I")
            throw std::runtime_error(path + ": axis " + std::string(a.name()) +
                                     " is not incremental (AxisType I): gonio needs a grid");
    const std::string type = cz.child("DataType").text().as_string();
    const pugi::xml_node dims = r3.child("MatrixDimension");
    MeasuredMap m;
    m.nx = int(number(dims, "SizeX", path));
    m.ny = int(number(dims, "SizeY", path));
    if (number(dims, "SizeZ", path, false, 1) != 1)
        throw std::runtime_error(path + ": SizeZ must be 1 (one layer of heights)");
    m.dx = number(cx, "Increment", path) * kMetresToUnit;
    m.dy = number(cy, "Increment", path) * kMetresToUnit;
    check_map_shape(m, path);
    const double z_increment = number(cz, "Increment", path, false, 1);
    const double z_offset = number(cz, "Offset", path, false, 0);
    size_t width = 0;
    if (type == "I")
        width = 2;
    else if (type == "L" || type == "F")
        width = 4;
    else if (type == "D")
        width = 8;
    else
        throw std::runtime_error(path + ": CZ data type " + quoted(type) +
                                 " (allowed: I, L, F, D)");
    const pugi::xml_node link = r3.child("DataLink");
    const std::string data_name = link.child("PointDataLink").text().as_string();
    if (data_name.empty())
        throw std::runtime_error(path + ": main.xml has no PointDataLink (inline point lists "
                                        "are not read)");
    const size_t count = m.z.size();
    const std::string data = zip.read(folder + data_name, count * width);
    if (data.size() != count * width)
        throw std::runtime_error(path + ": " + quoted(data_name) + " holds " +
                                 std::to_string(data.size()) + " bytes; " + std::to_string(m.nx) +
                                 " x " + std::to_string(m.ny) + " points of type " + type +
                                 " need " + std::to_string(count * width));
    if (const std::string sum =
            lower_trimmed(link.child("MD5ChecksumPointData").text().as_string());
        options.verify_checksums && !sum.empty() && sum != md5_hex(data))
        throw std::runtime_error(
            path + ": " + quoted(data_name) +
            " does not match its MD5 checksum in main.xml: the file is damaged "
            "(surface.input_checksums = false reads it)");
    for (size_t k = 0; k < count; ++k) {
        const char* p = data.data() + k * width;
        // Integers are counts of the Z increment from the offset; floats are lengths (ISO 5436-2).
        const double v = type == "I"   ? little_endian<std::int16_t>(p) * z_increment + z_offset
                         : type == "L" ? little_endian<std::int32_t>(p) * z_increment + z_offset
                         : type == "F" ? double(little_endian<float>(p))
                                       : little_endian<double>(p);
        m.z[k] = std::isfinite(v) ? v * kMetresToUnit : NAN;
    }
    // The optional bit array of valid points (bit k of byte k / 8, least significant first).
    if (const std::string valid = link.child("ValidPointsLink").text().as_string();
        !valid.empty()) {
        const std::string bits = zip.read(folder + valid, (count + 7) / 8);
        if (bits.size() < (count + 7) / 8)
            throw std::runtime_error(path + ": " + quoted(valid) + " is shorter than the points");
        for (size_t k = 0; k < count; ++k)
            if (!((static_cast<unsigned char>(bits[k / 8]) >> (k % 8)) & 1)) m.z[k] = NAN;
    }
    m.unit = kMeasuredUnit;
    m.note = "X3P, data type " + type + ", lengths in metres read as micrometres";
    return m;
}

bool x3p_recognises(const std::string& head) {
    // A zip whose first entry is not gonio's: X3P is the one zip format read here.
    return head.size() >= 4 && head.compare(0, 4, "PK\x03\x04") == 0;
}
} // namespace

const MeasuredFormat& x3p_format() {
    static const MeasuredFormat f{"x3p",
                                  "ISO 25178-72 XML (X3P): zip with main.xml, checksummed",
                                  {".x3p"},
                                  &x3p_recognises,
                                  &read_x3p};
    return f;
}

} // namespace gonio
