// gonio report of a gonio masking file: per case, the projected-area G1 and the weak furnace
// against theta_o beside Smith's G1 (analytic NDF and D_s), G1 by height quantile, and G2 slices
// (wo in the plane of incidence, both sides) against Smith's three forms.
#include "gonio/io/hdf5_handles.h"
#include "gonio/report/report.h"

#include <filesystem>
#include <stdexcept>

namespace gonio {

namespace {
using json = nlohmann::ordered_json;

h5::Handle open_checked(const std::string& path) {
    h5::silence_errors();
    if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no such file");
    h5::check_file_checksum(path); // before HDF5 parses a damaged file
    if (H5Fis_hdf5(path.c_str()) <= 0) throw std::runtime_error(path + ": not an HDF5 file");
    return h5::Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                      ("open " + path).c_str());
}
} // namespace

std::string file_format_of(const std::string& path) {
    const h5::Handle file = open_checked(path);
    if (H5Aexists(file, "file_format") <= 0) return "";
    return h5::read_string_attribute(file, "file_format");
}

nlohmann::json masking_report_data(const std::string& path) {
    const h5::Handle file = open_checked(path);
    try {
        h5::check_seal(file);
        json data;
        data["kind"] = "masking";
        data["file"] = std::filesystem::path(path).filename().string();
        json attrs = json::object();
        for (const char* k : {"gonio_version", "git_hash", "command_line", "config_path"})
            if (H5Aexists(file, k) > 0) attrs[k] = h5::read_string_attribute(file, k);
        data["attributes"] = attrs;
        json cases = json::array();
        for (const std::string& name : h5::read_string_list_attribute(file, "cases")) {
            const h5::Handle g(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose,
                               ("open group " + name).c_str());
            h5::check_seal(g);
            json c;
            c["name"] = name;
            c["ndf"] = h5::read_string_attribute(g, "ndf");
            c["surface"] = h5::read_string_attribute(g, "surface");
            for (const char* axis : {"theta_o", "phi_o", "theta_i", "phi_i", "g2_theta_o",
                                     "g2_dphi", "height_lower_edge"})
                c[axis] = h5::read_doubles(g, axis);
            json values = json::object();
            for (const char* d :
                 {"furnace", "furnace_stderr", "g1_projected", "g1_projected_stderr",
                  "g1_smith_ndf", "g1_smith_surface", "g1_height", "g1_height_stderr", "g2",
                  "g2_stderr", "g2_smith_uncorrelated_surface",
                  "g2_smith_height_correlated_surface",
                  "g2_smith_height_direction_correlated_surface", "g2_smith_height_correlated_ndf"})
                values[d] = h5::read_doubles(g, d);
            c["values"] = values;
            cases.push_back(c);
        }
        data["cases"] = cases;
        return nlohmann::json(data);
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
}

} // namespace gonio
