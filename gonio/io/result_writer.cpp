#include "gonio/io/result_writer.h"

#include "gonio_version.h"

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <hdf5_hl.h>
#include <stdexcept>
#include <unistd.h>

namespace gonio {

namespace {
std::vector<double> to_degrees(std::vector<double> v) {
    for (double& x : v) x = degrees(x);
    return v;
}
std::string utc_now() {
    std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    return buf;
}
} // namespace

std::string ResultWriter::conventions() {
    return "macro-surface normal n = +z; directions point away from the surface (i towards the "
           "light, o towards the sensor); theta from +z, phi from +x counter-clockwise; angles in "
           "files are in degrees; alpha is the Beckmann/GGX roughness (Beckmann slope standard "
           "deviation per axis = alpha/sqrt(2)); D is normalised so that integral D(m) (m.n) dw = "
           "1; "
           "brdf datasets hold cell averages f_c = E_c / projected_solid_angle_c in 1/sr, where "
           "E_c "
           "is the fraction of the incident power that leaves into cell c";
}

ResultWriter::ResultWriter(std::string path, bool overwrite) : path_(std::move(path)) {
    h5::silence_errors();
    if (!overwrite && std::filesystem::exists(path_))
        throw std::runtime_error(path_ + ": exists; pass --overwrite to replace it");
    tmp_path_ = path_ + ".tmp-" + std::to_string(::getpid());
    // Track link creation order so readers list the cases in config order, not by name.
    h5::Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "file creation property list");
    h5::check(H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
              "H5Pset_link_creation_order");
    file_ = h5::Handle(H5Fcreate(tmp_path_.c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT), H5Fclose,
                       ("create " + tmp_path_).c_str());
}

ResultWriter::~ResultWriter() {
    if (!committed_) {
        file_.reset();
        std::remove(tmp_path_.c_str());
    }
}

void ResultWriter::write_run(const Config& cfg, const std::string& command_line) {
    h5::write_string_attribute(file_, "file_format", "gonio-result 1");
    h5::write_string_attribute(file_, "gonio_version", kVersion);
    h5::write_string_attribute(file_, "git_hash", kGitHash);
    h5::write_string_attribute(file_, "command_line", command_line);
    h5::write_int_attribute(file_, "seed", static_cast<long long>(cfg.seed));
    h5::write_string_attribute(file_, "config_path", cfg.path);
    h5::write_string_attribute(file_, "config_toml", cfg.text);
    std::string overrides;
    for (const auto& o : cfg.overrides) overrides += o + "\n";
    h5::write_string_attribute(file_, "config_overrides", overrides);
    h5::write_string_attribute(file_, "config_effective_toml", cfg.effective_toml);
    h5::write_string_attribute(file_, "conventions", conventions());
    h5::write_string_attribute(file_, "created_utc", utc_now());
    std::string names;
    for (const auto& c : cfg.cases) names += (names.empty() ? "" : ",") + c.name;
    h5::write_string_attribute(file_, "cases", names);
}

void ResultWriter::write_model_case(const CaseConfig& c, const BeckersSensor& sensor,
                                    const ModelL1Result& r) {
    using h5::Handle;
    Handle gcpl(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "group creation property list");
    h5::check(H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
              "H5Pset_link_creation_order");
    Handle group(H5Gcreate2(file_, c.name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose,
                 ("create group " + c.name).c_str());
    h5::write_string_attribute(group, "name", c.name);
    h5::write_string_attribute(group, "ndf", make_ndf(c.ndf)->describe());
    h5::write_string_attribute(group, "material", c.material_type);
    h5::write_string_attribute(group, "fresnel", c.fresnel.describe());
    h5::write_string_attribute(group, "material_source", c.material_source);
    h5::write_string_attribute(group, "masking", masking_name(c.masking));
    h5::write_int_attribute(group, "quadrature_points", c.quadrature.points);
    h5::write_double_attribute(group, "quadrature_tolerance", c.quadrature.rel_tol);
    h5::write_int_attribute(group, "sensor_cells", sensor.cell_count());
    h5::write_string_attribute(group, "sensor", "Beckers & Beckers 2012 equal-area hemisphere");

    const size_t nt = c.theta_i_deg.size(), np = c.phi_i_deg.size();
    const size_t ncell = sensor.cell_count(), nc = c.fresnel.channels();

    Handle theta_i = h5::write_scale(group, "theta_i", c.theta_i_deg, "degree",
                                     "polar angle of the incident direction i");
    Handle phi_i = h5::write_scale(group, "phi_i", c.phi_i_deg, "degree",
                                   "azimuth of the incident direction i");
    std::vector<double> index(ncell), channel(nc);
    for (size_t k = 0; k < ncell; ++k) index[k] = static_cast<double>(k);
    for (size_t k = 0; k < nc; ++k) channel[k] = static_cast<double>(k);
    Handle cell = h5::write_scale(group, "cell", index, "", "sensor cell index", true);
    Handle chan = h5::write_scale(group, "channel", channel, "",
                                  nc == 1 && c.wavelengths_nm.empty()
                                      ? "spectral channel (achromatic material: one channel)"
                                      : "spectral channel",
                                  true);

    // Cell geometry: every coordinate is a dimension scale of the cell dimension.
    std::vector<std::pair<Handle, std::string>> cell_coords;
    auto coord = [&](const char* name, auto get, const char* units, const char* what, bool deg) {
        std::vector<double> v(ncell);
        for (size_t k = 0; k < ncell; ++k) v[k] = get(sensor.cell(static_cast<int>(k)));
        if (deg) v = to_degrees(v);
        cell_coords.emplace_back(h5::write_scale(group, name, v, units, what), name);
    };
    coord(
        "theta_center", [](const SensorCell& s) { return s.theta_center; }, "degree",
        "polar angle of the cell's equal-area centre", true);
    coord(
        "phi_center", [](const SensorCell& s) { return s.phi_center; }, "degree",
        "azimuth of the cell's centre", true);
    coord(
        "theta_min", [](const SensorCell& s) { return s.theta_min; }, "degree",
        "lower polar bound of the cell", true);
    coord(
        "theta_max", [](const SensorCell& s) { return s.theta_max; }, "degree",
        "upper polar bound of the cell", true);
    coord(
        "phi_min", [](const SensorCell& s) { return s.phi_min; }, "degree",
        "lower azimuth bound of the cell", true);
    coord(
        "phi_max", [](const SensorCell& s) { return s.phi_max; }, "degree",
        "upper azimuth bound of the cell", true);
    coord(
        "solid_angle", [](const SensorCell& s) { return s.solid_angle; }, "sr",
        "solid angle of the cell (2 pi / N)", false);
    coord(
        "projected_solid_angle", [](const SensorCell& s) { return s.projected_solid_angle; }, "sr",
        "integral of cos(theta) over the cell", false);
    std::vector<Handle> extra;
    if (!c.wavelengths_nm.empty())
        extra.push_back(h5::write_scale(group, "wavelength", c.wavelengths_nm, "nm",
                                        "wavelength of the channel"));

    std::vector<double> brdf(r.energy.size());
    for (size_t k = 0; k < brdf.size(); ++k) {
        const size_t cell_index = (k / nc) % ncell;
        brdf[k] = r.energy[k] / sensor.cell(static_cast<int>(cell_index)).projected_solid_angle;
    }
    const std::vector<hsize_t> dims4{nt, np, ncell, nc}, chunk4{1, 1, ncell, nc};
    Handle f =
        h5::write_dataset(group, "model_l1", dims4, chunk4, brdf.data(), "1/sr",
                          "Model L1: cell average of the specular microfacet BRDF [R19 Eq. 2]");
    Handle e = h5::write_dataset(group, "model_l1_energy", dims4, chunk4, r.energy.data(), "1",
                                 "Model L1: fraction of the incident power leaving into the cell");
    Handle a =
        h5::write_dataset(group, "model_l1_albedo", {nt, np, nc}, {1, 1, nc}, r.albedo.data(), "1",
                          "Model L1: directional albedo, integral of f cos(theta_o) dw_o");
    Handle t = h5::write_dataset(group, "model_l1_seconds", {nt, np}, {1, 1}, r.seconds.data(), "s",
                                 "wall time of the Model L1 evaluation");
    for (hid_t ds : {f.get(), e.get()}) {
        h5::check(H5DSattach_scale(ds, theta_i, 0), "attach theta_i");
        h5::check(H5DSattach_scale(ds, phi_i, 1), "attach phi_i");
        h5::check(H5DSattach_scale(ds, cell, 2), "attach cell");
        for (auto& [handle, name] : cell_coords)
            h5::check(H5DSattach_scale(ds, handle, 2), "attach cell coordinate");
        h5::check(H5DSattach_scale(ds, chan, 3), "attach channel");
        for (auto& w : extra) h5::check(H5DSattach_scale(ds, w, 3), "attach wavelength");
    }
    h5::check(H5DSattach_scale(a, theta_i, 0), "attach theta_i");
    h5::check(H5DSattach_scale(a, phi_i, 1), "attach phi_i");
    h5::check(H5DSattach_scale(a, chan, 2), "attach channel");
    for (auto& w : extra) h5::check(H5DSattach_scale(a, w, 2), "attach wavelength");
    h5::check(H5DSattach_scale(t, theta_i, 0), "attach theta_i");
    h5::check(H5DSattach_scale(t, phi_i, 1), "attach phi_i");
}

void ResultWriter::commit() {
    h5::check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush");
    file_.reset();
    std::error_code ec;
    std::filesystem::rename(tmp_path_, path_, ec);
    if (ec)
        throw std::runtime_error("cannot rename " + tmp_path_ + " to " + path_ + ": " +
                                 ec.message());
    committed_ = true;
}

} // namespace gonio
