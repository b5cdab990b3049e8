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

// A 1-D coordinate, float64 (or int32 when `integer`), made the dimension scale named `name`.
Handle write_scale(hid_t group, const std::string& name, const std::vector<double>& values,
                   const std::string& units, const std::string& long_name, bool integer = false);

// An N-D float64 dataset, chunked as `chunk`, deflate + shuffle, with units and long_name.
Handle write_dataset(hid_t group, const std::string& name, const std::vector<hsize_t>& dims,
                     const std::vector<hsize_t>& chunk, const double* data,
                     const std::string& units, const std::string& long_name);

std::vector<double> read_doubles(hid_t group, const std::string& name,
                                 std::vector<hsize_t>* dims = nullptr);

} // namespace gonio::h5
