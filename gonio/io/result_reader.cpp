#include "gonio/io/result_reader.h"

#include "gonio/io/hdf5_handles.h"

#include <cmath>
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

// Refusals name the dataset; read_result_summary adds the file.
[[noreturn]] void bad(const std::string& what) {
    throw std::runtime_error(what);
}

// An axis of the sweep or the sensor: 1-D, not empty, finite, increasing within [lo, hi].
std::vector<double> read_axis(hid_t group, const std::string& name, double lo, double hi,
                              bool increasing) {
    if (H5Lexists(group, name.c_str(), H5P_DEFAULT) <= 0) bad("no dataset " + name);
    std::vector<hsize_t> dims;
    std::vector<double> v = h5::read_doubles(group, name, &dims);
    if (dims.size() != 1 || v.empty()) bad(name + ": expected a non-empty 1-D axis");
    for (size_t k = 0; k < v.size(); ++k) {
        if (!std::isfinite(v[k]) || v[k] < lo || v[k] > hi)
            bad(name + ": value " + std::to_string(v[k]) + " outside [" + std::to_string(lo) +
                ", " + std::to_string(hi) + "]");
        if (increasing && k > 0 && !(v[k] > v[k - 1])) bad(name + ": not increasing");
    }
    return v;
}

// What a per-incidence dataset may hold, by its name: a fraction of the incident power (energies,
// albedos, the ledger) is finite and in [0, 1]; a BRDF, a model's map, an error or a count is
// finite and not negative; the ledger's unaccounted part and the achieved error are finite; a
// comparison with a model (infinite where the model is 0), a share or a time is not checked.
enum class Values { unchecked, finite, non_negative, fraction };
Values values_of(const std::string& name) {
    const auto has = [&](const char* part) { return name.find(part) != std::string::npos; };
    const auto starts = [&](const char* head) { return name.rfind(head, 0) == 0; };
    const auto ends = [&](const std::string& t) {
        return name.size() >= t.size() && name.compare(name.size() - t.size(), t.size(), t) == 0;
    };
    if (ends("_seconds") || has("_relative_difference") || has("_sigmas") || has("_distance") ||
        has("_ratio") || starts("surface_share_"))
        return Values::unchecked;
    if (name == "ledger_unaccounted" || name == "achieved_error") return Values::finite;
    if (ends("_stderr") || starts("model_") || starts("brdf") || starts("btdf") || name == "rays" ||
        name == "segments" || name == "rounds" || name == "realisations")
        return Values::non_negative;
    if (ends("_albedo") || starts("ledger_") || ends("energy")) return Values::fraction;
    return Values::finite;
}

void check_values(const std::string& name, const std::vector<double>& v) {
    const Values rule = values_of(name);
    if (rule == Values::unchecked) return;
    for (double x : v) {
        if (!std::isfinite(x)) bad(name + ": holds NaN or an infinite value");
        if (rule != Values::finite && x < -1e-9)
            bad(name + ": holds a negative value (" + std::to_string(x) + ")");
        if (rule == Values::fraction && x > 1 + 1e-6)
            bad(name + ": a fraction of the incident power above 1 (" + std::to_string(x) + ")");
    }
}

// The 1-D datasets of a case: its axes and the sensor cells' coordinates.
bool is_coordinate(const std::string& name) {
    for (const char* c : {"theta_i", "phi_i", "cell", "channel", "order", "model_order",
                          "wavelength", "theta_center", "phi_center", "theta_min", "theta_max",
                          "phi_min", "phi_max", "solid_angle", "projected_solid_angle"})
        if (name == c) return true;
    return false;
}

// One case's group: its axes checked, every per-incidence dataset's shape checked against them.
CaseSummary read_case(hid_t file, const std::string& name) {
    if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0)
        bad("case " + name + " is listed in the file's `cases` but its group is missing");
    h5::Handle group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose, "open group");
    try {
        h5::check_seal(group);
    } catch (const std::exception& e) {
        bad("case " + name + ": " + e.what());
    }
    CaseSummary c;
    c.name = name;
    c.attributes = string_attributes(group);
    c.models = list(group, "models");
    c.stop = list(group, "stop");
    c.timings = timings(group);
    c.theta_i_deg = read_axis(group, "theta_i", 0, 90, true);
    c.phi_i_deg = read_axis(group, "phi_i", 0, 360, true);
    c.cells = static_cast<int>(read_axis(group, "cell", 0, 1e9, true).size());
    c.channels = static_cast<int>(read_axis(group, "channel", 0, 1e9, true).size());
    if (H5Lexists(group, "wavelength", H5P_DEFAULT) > 0)
        c.wavelength_nm = read_axis(group, "wavelength", 1, 1e6, false);
    if (c.channels > 1 && c.wavelength_nm.size() != size_t(c.channels))
        bad("wavelength: " + std::to_string(c.wavelength_nm.size()) + " wavelengths for " +
            std::to_string(c.channels) + " channels");
    const hsize_t nt = c.theta_i_deg.size(), np = c.phi_i_deg.size();
    for (const std::string& ds : children(group, H5O_TYPE_DATASET)) {
        std::vector<hsize_t> dims;
        {
            h5::Handle d(H5Dopen2(group, ds.c_str(), H5P_DEFAULT), H5Dclose, "open dataset");
            h5::Handle space(H5Dget_space(d), H5Sclose, "dataspace");
            const int rank = H5Sget_simple_extent_ndims(space);
            if (rank == 1 && !is_coordinate(ds))
                bad(ds + ": a 1-D dataset where a quantity per incidence belongs");
            if (rank < 2 || rank > 5) continue; // an axis or a cell coordinate
            dims.resize(size_t(rank));
            H5Sget_simple_extent_dims(space, dims.data(), nullptr);
        }
        if (dims[0] != nt || dims[1] != np)
            bad(ds + ": shaped " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) +
                " ... for a sweep of " + std::to_string(nt) + " theta_i x " + std::to_string(np) +
                " phi_i");
        if (dims.size() >= 3 && dims.back() != hsize_t(c.channels))
            bad(ds + ": " + std::to_string(dims.back()) + " channels, the case " +
                std::to_string(c.channels));
        // Every quantity is read and checked (maps too: an export or a render reads them).
        std::vector<double> v = h5::read_doubles(group, ds);
        check_values(ds, v);
        if (dims.size() == 3)
            c.albedos[ds] = std::move(v);
        else if (dims.size() == 2)
            c.runs[ds] = std::move(v);
    }
    if (!c.stop.empty() && c.stop.size() != nt * np)
        bad("the attribute stop lists " + std::to_string(c.stop.size()) + " incidences of " +
            std::to_string(nt * np));
    return c;
}

} // namespace

ResultSummary read_result_summary(const std::string& path) {
    h5::silence_errors();
    if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no such file");
    try {
        h5::check_file_checksum(path); // before HDF5 parses a damaged file
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
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
    try {
        h5::check_seal(file);
        s.timings = timings(file);
        if (H5Aexists(file, "seed") <= 0) bad("no seed attribute");
        {
            h5::Handle attr(H5Aopen(file, "seed", H5P_DEFAULT), H5Aclose, "open attribute seed");
            h5::check(H5Aread(attr, H5T_NATIVE_LLONG, &s.seed), "read attribute seed");
        }
        // The cases the file lists, in order (a file without the list: its groups).
        std::vector<std::string> names = list(file, "cases");
        if (H5Aexists(file, "cases") <= 0) names = children(file, H5O_TYPE_GROUP);
        for (const std::string& name : names) s.cases.push_back(read_case(file, name));
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
    return s;
}

} // namespace gonio
