#pragma once
// RAII ownership of HDF5 identifiers and small helpers around the HDF5 C API and its
// dimension-scale (H5DS, hdf5_hl) interface. Every failing call throws std::runtime_error.
#include <hdf5.h>
#include <string>
#include <vector>

namespace gonio::h5 {

class Handle {
  public:
    using Closer = herr_t (*)(hid_t);
    Handle() = default;
    Handle(hid_t id, Closer closer, const char* what);
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& o) noexcept : id_(o.id_), closer_(o.closer_) { o.id_ = -1; }
    Handle& operator=(Handle&& o) noexcept;
    ~Handle() { reset(); }
    hid_t get() const { return id_; }
    operator hid_t() const { return id_; }
    void reset();
    // Gives the id up without closing it (the caller closed it and checks the result).
    void release() { id_ = -1; }

  private:
    hid_t id_ = -1;
    Closer closer_ = nullptr;
};

// Silences HDF5's own error printing: gonio reports errors itself.
void silence_errors();
// Throws std::runtime_error "HDF5: <what> failed (<reason>)" when status < 0.
void check(herr_t status, const char* what);
// Closes a file that is being thrown away (a write failed): its data are truncated first, so
// that the close's own flush has room even on a full disk. (A file whose close failed stays open
// in HDF5 1.10, whose exit handler then crashes closing it again.)
void discard_file(hid_t file);
// Why the last HDF5 call failed, in the system's words where a system call failed ("No space
// left on device"), else HDF5's innermost description; "" when unknown.
std::string reason();

// The name of link k of `group` in `order` (H5_INDEX_NAME or H5_INDEX_CRT_ORDER); throws
// std::runtime_error when the group's list of links is damaged.
std::string link_name(hid_t group, H5_index_t order, hsize_t k);

// Attributes (replaced if they exist). Strings are variable-length UTF-8; a list of strings is
// a 1-D array of them.
void write_string_attribute(hid_t object, const std::string& name, const std::string& value);
void write_string_list_attribute(hid_t object, const std::string& name,
                                 const std::vector<std::string>& values);
void write_double_attribute(hid_t object, const std::string& name, double value);
void write_int_attribute(hid_t object, const std::string& name, long long value);
// A scalar string attribute (fixed or variable length).
std::string read_string_attribute(hid_t object, const std::string& name);
// A string attribute as a list: the elements of an array, or a scalar split at `separator`
// (how format 1 stored lists; an empty string is an empty list).
std::vector<std::string> read_string_list_attribute(hid_t object, const std::string& name,
                                                    char separator = ',');
// Whether the attribute is an array (of more than one element or of none) rather than a scalar.
bool attribute_is_array(hid_t object, const std::string& name);
double read_double_attribute(hid_t object, const std::string& name);

// Dataset creation properties: chunked as `chunk` (at least 1 per axis), each chunk with a
// Fletcher-32 checksum HDF5 checks on reading.
Handle checksummed(const std::vector<hsize_t>& chunk);
// File access properties of the files gonio writes: object format of HDF5 1.8 and later, whose
// object headers, attributes included, carry checksums (h5py and xarray read them as any).
Handle checksummed_file_access();

// A 1-D coordinate, float64 (or int32 when `integer`), made the dimension scale named `name`.
Handle write_scale(hid_t group, const std::string& name, const std::vector<double>& values,
                   const std::string& units, const std::string& long_name, bool integer = false);

// An N-D float64 dataset, chunked as `chunk`, deflate + shuffle, with units and long_name.
Handle write_dataset(hid_t group, const std::string& name, const std::vector<hsize_t>& dims,
                     const std::vector<hsize_t>& chunk, const double* data,
                     const std::string& units, const std::string& long_name);

// A dataset's values as doubles; one gonio wrote is checked against the checksum of its values
// it stored (attribute gonio_crc32), so that a changed or damaged dataset is refused by name.
std::vector<double> read_doubles(hid_t group, const std::string& name,
                                 std::vector<hsize_t>* dims = nullptr);

// A whole-file checksum for the files gonio writes once (results, parts): HDF5 leaves the first
// kUserBlock bytes to its user; gonio puts there the CRC-32 of every byte after them, so that a
// damaged file is refused before HDF5 parses it (HDF5 1.10 may crash on damaged metadata).
inline constexpr hsize_t kUserBlock = 512;
// File creation properties with that user block.
Handle file_creation_with_checksum();
// After the file is closed: writes the checksum into its user block.
void write_file_checksum(const std::string& path);
// Throws std::runtime_error when the file carries a checksum that its bytes do not match
// (files without one, older or written by others, pass).
void check_file_checksum(const std::string& path);

// What gonio wrote, sealed: on a group, the list of its datasets (gonio_datasets) and, on any
// object, the list of its attributes (gonio_attributes) with the CRC-32 of their names and values
// (gonio_attributes_crc32). A reader then finds a missing dataset, and a changed, removed or
// damaged attribute (variable-length strings live outside HDF5's checksummed object headers).
// Attributes and datasets added later by others are not covered, nor refused.
void seal(hid_t object, bool group);
// Throws std::runtime_error saying what is missing or changed; objects without a seal pass.
void check_seal(hid_t object);

} // namespace gonio::h5
