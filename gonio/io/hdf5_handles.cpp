#include "gonio/io/hdf5_handles.h"

#include <hdf5_hl.h>
#include <stdexcept>

namespace gonio::h5 {

Handle::Handle(hid_t id, Closer closer, const char* what) : id_(id), closer_(closer) {
    if (id < 0) throw std::runtime_error(std::string("HDF5: ") + what + " failed");
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

void silence_errors() {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

void check(herr_t status, const char* what) {
    if (status < 0) throw std::runtime_error(std::string("HDF5: ") + what + " failed");
}

void write_string_attribute(hid_t object, const std::string& name, const std::string& value) {
    Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
    check(H5Tset_size(type, value.empty() ? 1 : value.size()), "H5Tset_size");
    check(H5Tset_cset(type, H5T_CSET_UTF8), "H5Tset_cset");
    check(H5Tset_strpad(type, H5T_STR_NULLPAD), "H5Tset_strpad");
    Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
    if (H5Aexists(object, name.c_str()) > 0) check(H5Adelete(object, name.c_str()), "H5Adelete");
    Handle attr(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                "attribute create");
    const std::string padded = value.empty() ? std::string(1, '\0') : value;
    check(H5Awrite(attr, type, padded.data()), "attribute write");
}

void write_double_attribute(hid_t object, const std::string& name, double value) {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
    Handle attr(H5Acreate2(object, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT),
                H5Aclose, "attribute create");
    check(H5Awrite(attr, H5T_NATIVE_DOUBLE, &value), "attribute write");
}

void write_int_attribute(hid_t object, const std::string& name, long long value) {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
    Handle attr(H5Acreate2(object, name.c_str(), H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT),
                H5Aclose, "attribute create");
    check(H5Awrite(attr, H5T_NATIVE_LLONG, &value), "attribute write");
}

bool has_attribute(hid_t object, const std::string& name) {
    return H5Aexists(object, name.c_str()) > 0;
}

std::string read_string_attribute(hid_t object, const std::string& name) {
    Handle attr(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose,
                ("open attribute " + name).c_str());
    Handle type(H5Aget_type(attr), H5Tclose, "attribute type");
    if (H5Tget_class(type) != H5T_STRING)
        throw std::runtime_error("HDF5: attribute " + name + " is not a string");
    if (H5Tis_variable_str(type) > 0) {
        Handle mem(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
        check(H5Tset_size(mem, H5T_VARIABLE), "H5Tset_size");
        char* value = nullptr;
        check(H5Aread(attr, mem, &value), "attribute read");
        std::string out = value ? value : "";
        H5free_memory(value);
        return out;
    }
    const size_t size = H5Tget_size(type);
    std::string out(size, '\0');
    check(H5Aread(attr, type, out.data()), "attribute read");
    out.resize(out.find('\0') == std::string::npos ? out.size() : out.find('\0'));
    return out;
}

Handle write_scale(hid_t group, const std::string& name, const std::vector<double>& values,
                   const std::string& units, const std::string& description, bool integer) {
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
    if (!units.empty()) write_string_attribute(ds, "units", units);
    write_string_attribute(ds, "long_name", description);
    return ds;
}

Handle write_dataset(hid_t group, const std::string& name, const std::vector<hsize_t>& dims,
                     const std::vector<hsize_t>& chunk, const double* data,
                     const std::string& units, const std::string& description) {
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
    if (!units.empty()) write_string_attribute(ds, "units", units);
    write_string_attribute(ds, "long_name", description);
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
