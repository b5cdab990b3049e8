#include "gonio/io/hdf5_handles.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <hdf5_hl.h>
#include <stdexcept>
#include <unistd.h>
#include <zlib.h>

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

Handle checksummed(const std::vector<hsize_t>& chunk) {
    Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "property list");
    std::vector<hsize_t> c = chunk;
    for (hsize_t& x : c) x = std::max<hsize_t>(x, 1);
    check(H5Pset_chunk(plist, static_cast<int>(c.size()), c.data()), "H5Pset_chunk");
    check(H5Pset_fletcher32(plist), "H5Pset_fletcher32");
    return plist;
}

Handle checksummed_file_access() {
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access property list");
    check(H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST), "H5Pset_libver_bounds");
    return fapl;
}

namespace {
// CRC-32 of doubles, as 8 hex digits.
std::string values_crc(const std::vector<double>& v) {
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(v.data()),
                            uInt(v.size() * sizeof(double)));
    char text[16];
    std::snprintf(text, sizeof text, "%08lx", static_cast<unsigned long>(crc));
    return text;
}

// Every attribute of an object, by name.
std::vector<std::string> attribute_names(hid_t object) {
    H5O_info_t info;
    check(H5Oget_info2(object, &info, H5O_INFO_NUM_ATTRS), "H5Oget_info");
    std::vector<std::string> names;
    for (hsize_t k = 0; k < info.num_attrs; ++k) {
        Handle attr(
            H5Aopen_by_idx(object, ".", H5_INDEX_NAME, H5_ITER_INC, k, H5P_DEFAULT, H5P_DEFAULT),
            H5Aclose, "open attribute");
        const ssize_t len = H5Aget_name(attr, 0, nullptr);
        std::string name(size_t(std::max<ssize_t>(len, 0)), '\0');
        H5Aget_name(attr, len + 1, name.data());
        names.push_back(name);
    }
    return names;
}

// An attribute's value as text: strings as they are, a list joined, numbers by their bytes.
std::string attribute_text(hid_t object, const std::string& name) {
    if (H5Aexists(object, name.c_str()) <= 0)
        throw std::runtime_error("attribute " + name + " is missing");
    Handle attr(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose,
                ("open attribute " + name).c_str());
    Handle type(H5Aget_type(attr), H5Tclose, "attribute type");
    if (H5Tget_class(type) == H5T_STRING) {
        std::string joined;
        for (const std::string& s : read_string_list_attribute(object, name, '\x1f'))
            joined += s + '\x1f';
        return joined;
    }
    Handle space(H5Aget_space(attr), H5Sclose, "attribute space");
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    if (n < 0 || n > (1 << 20)) throw std::runtime_error("attribute " + name + " is damaged");
    std::vector<double> v(static_cast<size_t>(n));
    if (n > 0)
        check(H5Aread(attr, H5T_NATIVE_DOUBLE, v.data()), ("read attribute " + name).c_str());
    return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
}

std::string attributes_crc(hid_t object, const std::vector<std::string>& names) {
    uLong crc = crc32(0L, Z_NULL, 0);
    for (const std::string& name : names) {
        const std::string text = name + '\0' + attribute_text(object, name) + '\0';
        crc = crc32(crc, reinterpret_cast<const Bytef*>(text.data()), uInt(text.size()));
    }
    char hex[16];
    std::snprintf(hex, sizeof hex, "%08lx", static_cast<unsigned long>(crc));
    return hex;
}

bool sealing(const std::string& name) {
    return name == "gonio_attributes" || name == "gonio_attributes_crc32";
}
} // namespace

namespace {
constexpr char kChecksumTag[] = "gonio file crc32 ";

unsigned long crc_after_user_block(std::istream& in) {
    in.seekg(std::streamoff(kUserBlock));
    uLong crc = crc32(0L, Z_NULL, 0);
    std::vector<char> buffer(1 << 20);
    while (in) {
        in.read(buffer.data(), std::streamsize(buffer.size()));
        const std::streamsize got = in.gcount();
        if (got > 0) crc = crc32(crc, reinterpret_cast<const Bytef*>(buffer.data()), uInt(got));
    }
    return static_cast<unsigned long>(crc);
}
} // namespace

Handle file_creation_with_checksum() {
    Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "file creation property list");
    check(H5Pset_userblock(fcpl, kUserBlock), "H5Pset_userblock");
    return fcpl;
}

void write_file_checksum(const std::string& path) {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    if (!f) throw std::runtime_error("cannot reopen to write its checksum");
    const unsigned long crc = crc_after_user_block(f);
    f.clear();
    char tag[64];
    std::snprintf(tag, sizeof tag, "%s%08lx\n", kChecksumTag, crc);
    f.seekp(0);
    f.write(tag, std::streamsize(std::strlen(tag)));
    f.flush();
    if (!f) throw std::runtime_error("cannot write its checksum");
}

void check_file_checksum(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    char head[64] = {};
    f.read(head, sizeof kChecksumTag - 1 + 8);
    if (!f || std::strncmp(head, kChecksumTag, sizeof kChecksumTag - 1) != 0) return;
    const std::string stored(head + sizeof kChecksumTag - 1, 8);
    char now[16];
    std::snprintf(now, sizeof now, "%08lx", crc_after_user_block(f));
    if (stored != now)
        throw std::runtime_error("damaged, or changed since gonio wrote it (its checksum does "
                                 "not match its bytes)");
}

std::string link_name(hid_t group, H5_index_t order, hsize_t k) {
    const ssize_t len =
        H5Lget_name_by_idx(group, ".", order, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    if (len < 0) throw std::runtime_error("a damaged list of links");
    std::string name(size_t(len), '\0');
    if (H5Lget_name_by_idx(group, ".", order, H5_ITER_INC, k, name.data(), size_t(len) + 1,
                           H5P_DEFAULT) < 0)
        throw std::runtime_error("a damaged list of links");
    return name;
}

void seal(hid_t object, bool group) {
    if (group) {
        std::vector<std::string> datasets;
        H5G_info_t info;
        check(H5Gget_info(object, &info), "H5Gget_info");
        for (hsize_t k = 0; k < info.nlinks; ++k) {
            const std::string name = link_name(object, H5_INDEX_NAME, k);
            H5O_info_t o;
            if (H5Oget_info_by_name2(object, name.c_str(), &o, H5O_INFO_BASIC, H5P_DEFAULT) >= 0 &&
                o.type == H5O_TYPE_DATASET)
                datasets.push_back(name);
        }
        write_string_list_attribute(object, "gonio_datasets", datasets);
    }
    std::vector<std::string> names;
    for (const std::string& n : attribute_names(object))
        if (!sealing(n)) names.push_back(n);
    write_string_list_attribute(object, "gonio_attributes", names);
    write_string_attribute(object, "gonio_attributes_crc32", attributes_crc(object, names));
}

void check_seal(hid_t object) {
    if (H5Aexists(object, "gonio_attributes_crc32") <= 0) return; // not sealed (an older file)
    const std::vector<std::string> names = read_string_list_attribute(object, "gonio_attributes");
    if (attributes_crc(object, names) != read_string_attribute(object, "gonio_attributes_crc32"))
        throw std::runtime_error("its attributes were changed or damaged since gonio wrote them "
                                 "(their checksum does not match)");
    if (H5Aexists(object, "gonio_datasets") > 0)
        for (const std::string& d : read_string_list_attribute(object, "gonio_datasets")) {
            if (H5Lexists(object, d.c_str(), H5P_DEFAULT) <= 0)
                throw std::runtime_error("dataset " + d + " is missing");
            Handle ds(H5Dopen2(object, d.c_str(), H5P_DEFAULT), H5Dclose, ("open " + d).c_str());
            if (H5Aexists(ds, "gonio_crc32") <= 0) // replaced by another dataset of its name
                throw std::runtime_error("dataset " + d + " is not the one gonio wrote");
        }
}

Handle write_scale(hid_t group, const std::string& name, const std::vector<double>& values,
                   const std::string& units, const std::string& long_name, bool integer) {
    const hsize_t n = values.size();
    Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose, "dataspace");
    Handle plist = checksummed({n});
    Handle ds(H5Dcreate2(group, name.c_str(), integer ? H5T_STD_I32LE : H5T_IEEE_F64LE, space,
                         H5P_DEFAULT, plist, H5P_DEFAULT),
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
    write_string_attribute(ds, "gonio_crc32", values_crc(values));
    return ds;
}

Handle write_dataset(hid_t group, const std::string& name, const std::vector<hsize_t>& dims,
                     const std::vector<hsize_t>& chunk, const double* data,
                     const std::string& units, const std::string& long_name) {
    Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
                 "dataspace");
    Handle plist = checksummed(chunk);
    check(H5Pset_shuffle(plist), "H5Pset_shuffle");
    check(H5Pset_deflate(plist, 4), "H5Pset_deflate");
    Handle ds(
        H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, plist, H5P_DEFAULT),
        H5Dclose, ("create " + name).c_str());
    check(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write");
    write_string_attribute(ds, "units", units);
    write_string_attribute(ds, "long_name", long_name);
    hsize_t total = 1;
    for (hsize_t d : dims) total *= d;
    write_string_attribute(ds, "gonio_crc32", values_crc(std::vector<double>(data, data + total)));
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
    if (H5Aexists(ds, "gonio_crc32") > 0 &&
        read_string_attribute(ds, "gonio_crc32") != values_crc(out))
        throw std::runtime_error(name + ": its values were changed or damaged since gonio wrote "
                                        "them (their checksum does not match)");
    if (dims) *dims = d;
    return out;
}

} // namespace gonio::h5
