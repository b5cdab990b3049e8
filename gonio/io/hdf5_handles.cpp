#include "gonio/io/hdf5_handles.h"

#include <hdf5_hl.h>
#include <stdexcept>
#include <unistd.h>

namespace gonio::h5 {

namespace {
// The innermost entry of HDF5's error stack, where the failure was first detected.
herr_t innermost(unsigned n, const H5E_error2_t* e, void* out) {
    if (n == 0 && e->desc) *static_cast<std::string*>(out) = e->desc;
    return 0;
}

std::string failure(const std::string& what) {
    const std::string why = reason();
    return "HDF5: " + what + " failed" + (why.empty() ? "" : " (" + why + ")");
}
} // namespace

std::string reason() {
    std::string desc;
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost, &desc);
    // A system call's failure carries the system's words: "error message = 'No space left ...'".
    const std::string tag = "error message = '";
    if (const size_t at = desc.find(tag); at != std::string::npos) {
        const size_t from = at + tag.size(), to = desc.find('\'', from);
        return desc.substr(from, to == std::string::npos ? std::string::npos : to - from);
    }
    return desc.size() > 200 ? desc.substr(0, 200) + "..." : desc;
}

Handle::Handle(hid_t id, Closer closer, const char* what) : id_(id), closer_(closer) {
    if (id < 0) throw std::runtime_error(failure(what));
}

Handle& Handle::operator=(Handle&& o) noexcept {
    if (this != &o) {
        reset();
        id_ = o.id_;
        closer_ = o.closer_;
        o.id_ = -1;
    }
    return *this;
}

void Handle::reset() {
    if (id_ >= 0 && closer_) closer_(id_);
    id_ = -1;
}

void discard_file(hid_t file) {
    if (file < 0) return;
    void* fd = nullptr;
    if (H5Fget_vfd_handle(file, H5P_DEFAULT, &fd) >= 0 && fd) [[maybe_unused]]
        const int ignored = ::ftruncate(*static_cast<int*>(fd), 0);
    if (H5Fclose(file) < 0) H5Fclose(file); // the flush failed once: it has room now
}

void silence_errors() {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

void check(herr_t status, const char* what) {
    if (status < 0) throw std::runtime_error(failure(what));
}

namespace {

// Variable-length UTF-8 strings, in the file and in memory.
Handle utf8_type() {
    Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
    check(H5Tset_size(type, H5T_VARIABLE), "H5Tset_size");
    check(H5Tset_cset(type, H5T_CSET_UTF8), "H5Tset_cset");
    return type;
}

Handle replace_attribute(hid_t object, const std::string& name, hid_t type, hid_t space) {
    if (H5Aexists(object, name.c_str()) > 0) check(H5Adelete(object, name.c_str()), "H5Adelete");
    return Handle(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                  ("create attribute " + name).c_str());
}

} // namespace

void write_string_attribute(hid_t object, const std::string& name, const std::string& value) {
    Handle type = utf8_type();
    Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
    Handle attr = replace_attribute(object, name, type, space);
    const char* p = value.c_str();
    check(H5Awrite(attr, type, &p), "attribute write");
}

void write_string_list_attribute(hid_t object, const std::string& name,
                                 const std::vector<std::string>& values) {
    Handle type = utf8_type();
    const hsize_t n = values.size();
    Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose, "dataspace");
    Handle attr = replace_attribute(object, name, type, space);
    std::vector<const char*> p;
    for (const std::string& v : values) p.push_back(v.c_str());
    if (n) check(H5Awrite(attr, type, p.data()), "attribute write");
}

void write_double_attribute(hid_t object, const std::string& name, double value) {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
    Handle attr = replace_attribute(object, name, H5T_IEEE_F64LE, space);
    check(H5Awrite(attr, H5T_NATIVE_DOUBLE, &value), "attribute write");
}

void write_int_attribute(hid_t object, const std::string& name, long long value) {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
    Handle attr = replace_attribute(object, name, H5T_STD_I64LE, space);
    check(H5Awrite(attr, H5T_NATIVE_LLONG, &value), "attribute write");
}

double read_double_attribute(hid_t object, const std::string& name) {
    Handle attr(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose,
                ("open attribute " + name).c_str());
    double value = 0;
    check(H5Aread(attr, H5T_NATIVE_DOUBLE, &value), ("read attribute " + name).c_str());
    return value;
}

bool attribute_is_array(hid_t object, const std::string& name) {
    Handle attr(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose,
                ("open attribute " + name).c_str());
    Handle space(H5Aget_space(attr), H5Sclose, "attribute space");
    return H5Sget_simple_extent_type(space) == H5S_SIMPLE;
}

namespace {

// Every element of a string attribute (one for a scalar).
std::vector<std::string> read_strings(hid_t object, const std::string& name) {
    Handle attr(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose,
                ("open attribute " + name).c_str());
    Handle type(H5Aget_type(attr), H5Tclose, "attribute type");
    if (H5Tget_class(type) != H5T_STRING)
        throw std::runtime_error("HDF5: attribute " + name + " is not a string");
    Handle space(H5Aget_space(attr), H5Sclose, "attribute space");
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    std::vector<std::string> out;
    if (n <= 0) return out;
    if (H5Tis_variable_str(type) > 0) {
        Handle mem(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
        check(H5Tset_size(mem, H5T_VARIABLE), "H5Tset_size");
        check(H5Tset_cset(mem, H5Tget_cset(type)), "H5Tset_cset");
        std::vector<char*> values(size_t(n), nullptr);
        check(H5Aread(attr, mem, values.data()), "attribute read");
        for (char* v : values) {
            out.push_back(v ? v : "");
            H5free_memory(v);
        }
        return out;
    }
    const size_t size = H5Tget_size(type);
    std::string buffer(size * size_t(n), '\0');
    check(H5Aread(attr, type, buffer.data()), "attribute read");
    for (hssize_t k = 0; k < n; ++k) {
        std::string v = buffer.substr(size_t(k) * size, size);
        out.push_back(v.substr(0, v.find('\0')));
    }
    return out;
}

} // namespace

std::string read_string_attribute(hid_t object, const std::string& name) {
    const std::vector<std::string> v = read_strings(object, name);
    if (v.size() != 1)
        throw std::runtime_error("HDF5: attribute " + name + " is not a single string");
    return v[0];
}

std::vector<std::string> read_string_list_attribute(hid_t object, const std::string& name,
                                                    char separator) {
    if (attribute_is_array(object, name)) return read_strings(object, name);
    const std::string joined = read_string_attribute(object, name);
    std::vector<std::string> out;
    if (joined.empty()) return out;
    size_t from = 0;
    for (size_t at; (at = joined.find(separator, from)) != std::string::npos; from = at + 1)
        out.push_back(joined.substr(from, at - from));
    out.push_back(joined.substr(from));
    return out;
}

Handle write_scale(hid_t group, const std::string& name, const std::vector<double>& values,
                   const std::string& units, const std::string& long_name, bool integer) {
    const hsize_t n = values.size();
    Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose, "dataspace");
    Handle ds(H5Dcreate2(group, name.c_str(), integer ? H5T_STD_I32LE : H5T_IEEE_F64LE, space,
                         H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              H5Dclose, ("create " + name).c_str());
    if (integer) {
        std::vector<int> iv(values.begin(), values.end());
        check(H5Dwrite(ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, iv.data()), "write");
    } else {
        check(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
              "write");
    }
    check(H5DSset_scale(ds, name.c_str()), "H5DSset_scale");
    write_string_attribute(ds, "units", units);
    write_string_attribute(ds, "long_name", long_name);
    return ds;
}

Handle write_dataset(hid_t group, const std::string& name, const std::vector<hsize_t>& dims,
                     const std::vector<hsize_t>& chunk, const double* data,
                     const std::string& units, const std::string& long_name) {
    Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
                 "dataspace");
    Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "property list");
    check(H5Pset_chunk(plist, static_cast<int>(chunk.size()), chunk.data()), "H5Pset_chunk");
    check(H5Pset_shuffle(plist), "H5Pset_shuffle");
    check(H5Pset_deflate(plist, 4), "H5Pset_deflate");
    Handle ds(
        H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, plist, H5P_DEFAULT),
        H5Dclose, ("create " + name).c_str());
    check(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write");
    write_string_attribute(ds, "units", units);
    write_string_attribute(ds, "long_name", long_name);
    return ds;
}

std::vector<double> read_doubles(hid_t group, const std::string& name, std::vector<hsize_t>* dims) {
    Handle ds(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose, ("open " + name).c_str());
    Handle space(H5Dget_space(ds), H5Sclose, "dataspace");
    const int rank = H5Sget_simple_extent_ndims(space);
    std::vector<hsize_t> d(rank > 0 ? rank : 0);
    if (rank > 0) H5Sget_simple_extent_dims(space, d.data(), nullptr);
    hsize_t total = 1;
    for (hsize_t x : d) total *= x;
    std::vector<double> out(total);
    if (total)
        check(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()),
              ("read " + name).c_str());
    if (dims) *dims = d;
    return out;
}

} // namespace gonio::h5
