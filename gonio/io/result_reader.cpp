#include "gonio/io/result_reader.h"

#include "gonio/io/hdf5_handles.h"

#include <filesystem>
#include <stdexcept>

namespace gonio {

namespace {

std::vector<std::string> children(hid_t group, H5O_type_t type) {
    std::vector<std::string> names;
    H5G_info_t info;
    h5::check(H5Gget_info(group, &info), "H5Gget_info");
    for (hsize_t k = 0; k < info.nlinks; ++k) {
        const ssize_t len = H5Lget_name_by_idx(group, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, k,
                                               nullptr, 0, H5P_DEFAULT);
        std::string name;
        if (len < 0) {
            const ssize_t l2 = H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k,
                                                  nullptr, 0, H5P_DEFAULT);
            name.resize(l2);
            H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), l2 + 1,
                               H5P_DEFAULT);
        } else {
            name.resize(len);
            H5Lget_name_by_idx(group, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, k, name.data(), len + 1,
                               H5P_DEFAULT);
        }
        H5O_info_t oinfo;
        if (H5Oget_info_by_name2(group, name.c_str(), &oinfo, H5O_INFO_BASIC, H5P_DEFAULT) >= 0 &&
            oinfo.type == type)
            names.push_back(name);
    }
    return names;
}

std::map<std::string, std::string> string_attributes(hid_t object) {
    std::map<std::string, std::string> out;
    H5O_info_t info;
    h5::check(H5Oget_info2(object, &info, H5O_INFO_NUM_ATTRS), "H5Oget_info");
    for (hsize_t k = 0; k < info.num_attrs; ++k) {
        h5::Handle attr(
            H5Aopen_by_idx(object, ".", H5_INDEX_NAME, H5_ITER_INC, k, H5P_DEFAULT, H5P_DEFAULT),
            H5Aclose, "open attribute");
        const ssize_t len = H5Aget_name(attr, 0, nullptr);
        std::string name(len, '\0');
        H5Aget_name(attr, len + 1, name.data());
        h5::Handle type(H5Aget_type(attr), H5Tclose, "attribute type");
        if (H5Tget_class(type) == H5T_STRING && !h5::attribute_is_array(object, name))
            out[name] = h5::read_string_attribute(object, name);
    }
    return out;
}

// A list attribute (a string array in format 2, comma-separated in format 1); empty if absent.
std::vector<std::string> list(hid_t object, const std::string& name) {
    if (H5Aexists(object, name.c_str()) <= 0) return {};
    return h5::read_string_list_attribute(object, name, ',');
}

// The phases listed in `phases` with their phase_<name>_seconds (format 2; none in format 1).
std::vector<std::pair<std::string, double>> timings(hid_t object) {
    std::vector<std::pair<std::string, double>> out;
    for (const std::string& phase : list(object, "phases"))
        out.emplace_back(phase, h5::read_double_attribute(object, "phase_" + phase + "_seconds"));
    return out;
}

} // namespace

ResultSummary read_result_summary(const std::string& path) {
    h5::silence_errors();
    if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no such file");
    if (H5Fis_hdf5(path.c_str()) <= 0) throw std::runtime_error(path + ": not an HDF5 file");
    h5::Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                    ("open " + path).c_str());
    ResultSummary s;
    s.path = path;
    s.attributes = string_attributes(file);
    const auto format = s.attributes.find("file_format");
    if (format == s.attributes.end())
        throw std::runtime_error(path + ": not a gonio result file (no file_format attribute)");
    if (format->second == "gonio-result 1")
        s.format = 1;
    else if (format->second == "gonio-result 2")
        s.format = 2;
    else
        throw std::runtime_error(path + ": unknown file format '" + format->second +
                                 "' (this gonio reads gonio-result 1 and 2)");
    s.timings = timings(file);
    {
        h5::Handle attr(H5Aopen(file, "seed", H5P_DEFAULT), H5Aclose, "open seed");
        h5::check(H5Aread(attr, H5T_NATIVE_LLONG, &s.seed), "read seed");
    }
    for (const std::string& name : children(file, H5O_TYPE_GROUP)) {
        h5::Handle group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose, "open group");
        CaseSummary c;
        c.name = name;
        c.attributes = string_attributes(group);
        c.models = list(group, "models");
        c.stop = list(group, "stop");
        c.timings = timings(group);
        c.theta_i_deg = h5::read_doubles(group, "theta_i");
        c.phi_i_deg = h5::read_doubles(group, "phi_i");
        c.cells = static_cast<int>(h5::read_doubles(group, "cell").size());
        c.channels = static_cast<int>(h5::read_doubles(group, "channel").size());
        if (H5Lexists(group, "wavelength", H5P_DEFAULT) > 0)
            c.wavelength_nm = h5::read_doubles(group, "wavelength");
        for (const std::string& ds : children(group, H5O_TYPE_DATASET)) {
            std::vector<hsize_t> dims;
            {
                h5::Handle d(H5Dopen2(group, ds.c_str(), H5P_DEFAULT), H5Dclose, "open dataset");
                h5::Handle space(H5Dget_space(d), H5Sclose, "dataspace");
                const int rank = H5Sget_simple_extent_ndims(space);
                if (rank != 2 && rank != 3) continue;
                dims.resize(size_t(rank));
                H5Sget_simple_extent_dims(space, dims.data(), nullptr);
            }
            if (dims[0] != c.theta_i_deg.size() || dims[1] != c.phi_i_deg.size()) continue;
            if (dims.size() == 3 && dims[2] == hsize_t(c.channels))
                c.albedos[ds] = h5::read_doubles(group, ds);
            else if (dims.size() == 2)
                c.runs[ds] = h5::read_doubles(group, ds);
        }
        s.cases.push_back(std::move(c));
    }
    return s;
}

} // namespace gonio
