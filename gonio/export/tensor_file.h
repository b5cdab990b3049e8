#pragma once
// Writer of the "tensor_file" container that the RGL measured-BSDF readers load (Mitsuba 3
// src/core/tensor.cpp, pbrt-v4 bxdfs.cpp, rgl-epfl/brdf-loader): little-endian, the 12 bytes
// "tensor_file\0", version (1, 0), a u32 field count, then per field: u16 name length, the name,
// u16 rank, u8 dtype, u64 absolute offset of its data, u64 shape[rank]; each field's data, C order,
// starts on an 8-byte boundary after the header.
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace gonio {

class TensorFileWriter {
  public:
    void add_u8(const std::string& name, std::vector<std::uint64_t> shape,
                std::vector<std::uint8_t> data);
    void add_f32(const std::string& name, std::vector<std::uint64_t> shape,
                 const std::vector<double>& data);
    void write(std::ostream& out) const;

    enum DType : std::uint8_t { kUInt8 = 1, kFloat32 = 10 }; // the format's dtype codes

  private:
    struct Field {
        std::string name;
        std::vector<std::uint64_t> shape;
        DType dtype;
        std::vector<std::uint8_t> bytes; // little-endian elements
    };
    std::vector<Field> fields_;
};

} // namespace gonio
