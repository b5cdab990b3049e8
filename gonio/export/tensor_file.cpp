#include "gonio/export/tensor_file.h"

#include "core/check.h"

#include <cstring>
#include <stdexcept>

namespace gonio {

namespace {
static_assert(sizeof(float) == 4, "float32 expected");
bool little_endian() {
    const std::uint16_t one = 1;
    std::uint8_t b;
    std::memcpy(&b, &one, 1);
    return b == 1;
}
template <class T>
void put(std::vector<std::uint8_t>& out, T v) {
    std::uint8_t b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (!little_endian())
        for (size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
    out.insert(out.end(), b, b + sizeof(T));
}
std::uint64_t count(const std::vector<std::uint64_t>& shape) {
    std::uint64_t n = 1;
    for (auto s : shape) n *= s;
    return n;
}
} // namespace

void TensorFileWriter::add_u8(const std::string& name, std::vector<std::uint64_t> shape,
                              std::vector<std::uint8_t> data) {
    GONIO_CHECK_MSG(data.size() == count(shape), name + " has the wrong number of values");
    fields_.push_back({name, std::move(shape), kUInt8, std::move(data)});
}

void TensorFileWriter::add_f32(const std::string& name, std::vector<std::uint64_t> shape,
                               const std::vector<double>& data) {
    GONIO_CHECK_MSG(data.size() == count(shape), name + " has the wrong number of values");
    Field f{name, std::move(shape), kFloat32, {}};
    f.bytes.reserve(data.size() * 4);
    for (double v : data) put(f.bytes, static_cast<float>(v));
    fields_.push_back(std::move(f));
}

void TensorFileWriter::write(std::ostream& out) const {
    std::uint64_t header = 12 + 2 + 4;
    for (const Field& f : fields_) header += 2 + f.name.size() + 2 + 1 + 8 + 8 * f.shape.size();
    auto align = [](std::uint64_t x) { return (x + 7) / 8 * 8; };
    std::vector<std::uint8_t> h;
    const char magic[12] = {'t', 'e', 'n', 's', 'o', 'r', '_', 'f', 'i', 'l', 'e', '\0'};
    h.insert(h.end(), magic, magic + 12);
    h.push_back(1); // version 1.0
    h.push_back(0);
    put(h, static_cast<std::uint32_t>(fields_.size()));
    std::uint64_t offset = align(header);
    for (const Field& f : fields_) {
        put(h, static_cast<std::uint16_t>(f.name.size()));
        h.insert(h.end(), f.name.begin(), f.name.end());
        put(h, static_cast<std::uint16_t>(f.shape.size()));
        h.push_back(f.dtype);
        put(h, offset);
        for (auto s : f.shape) put(h, s);
        offset = align(offset + f.bytes.size());
    }
    h.resize(align(header), 0);
    out.write(reinterpret_cast<const char*>(h.data()), std::streamsize(h.size()));
    for (const Field& f : fields_) {
        std::vector<std::uint8_t> block = f.bytes;
        block.resize(align(block.size()), 0);
        out.write(reinterpret_cast<const char*>(block.data()), std::streamsize(block.size()));
    }
}

} // namespace gonio
