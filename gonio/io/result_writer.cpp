#include "gonio/io/result_writer.h"

#include "core/check.h"
#include "core/output_files.h"
#include "gonio_version.h"

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <hdf5_hl.h>
#include <map>
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

ResultWriter::ResultWriter(std::string path, bool overwrite)
    : file_(std::move(path), overwrite, "a result file") {}

void write_provenance(hid_t file, const std::string& format, const Config& cfg,
                      const std::string& command_line) {
    h5::write_string_attribute(file, "file_format", format);
    h5::write_string_attribute(file, "gonio_version", kVersion);
    h5::write_string_attribute(file, "git_hash", kGitHash);
    h5::write_string_attribute(file, "command_line", command_line);
    h5::write_int_attribute(file, "seed", static_cast<long long>(cfg.seed));
    h5::write_string_attribute(file, "config_path", cfg.path);
    h5::write_string_attribute(file, "config_effective_toml", cfg.effective_toml);
}

void ResultWriter::write_run(const Config& cfg, const std::string& command_line) {
    write_provenance(file_, "gonio-result 2", cfg, command_line);
    h5::write_string_attribute(file_, "config_toml", cfg.text);
    std::string overrides;
    for (const auto& o : cfg.overrides) overrides += o + "\n";
    h5::write_string_attribute(file_, "config_overrides", overrides);
    h5::write_string_attribute(file_, "conventions", conventions());
    h5::write_string_attribute(file_, "created_utc", utc_now());
    std::vector<std::string> names;
    for (const auto& c : cfg.cases) names.push_back(c.name);
    h5::write_string_list_attribute(file_, "cases", names);
}

void ResultWriter::write_execution(int ranks, int threads, int merged_parts) {
    h5::write_string_attribute(file_, "mpi_ranks", std::to_string(ranks));
    h5::write_string_attribute(file_, "threads_per_rank", std::to_string(threads));
    if (merged_parts > 0)
        h5::write_string_attribute(file_, "merged_parts", std::to_string(merged_parts));
}

void ResultWriter::write_memory(double estimate, double peak) {
    h5::write_string_attribute(file_, "memory_estimate_bytes", std::to_string((long long)estimate));
    h5::write_string_attribute(file_, "memory_peak_bytes", std::to_string((long long)peak));
}

// A case's group with its dimension scales, one per axis, and the names of the coordinate
// variables along cell and channel; put() writes a named array against them.
struct ResultWriter::CaseGroup {
    h5::Handle group;
    std::map<std::string, h5::Handle> scales; // dimension name -> its scale
    std::string cell_coordinates, channel_coordinates;

    void add_scale(const std::string& name, const std::vector<double>& values,
                   const std::string& units, const std::string& long_name, bool integer) {
        scales[name] = h5::write_scale(group, name, values, units, long_name, integer);
    }
    // A 1-D variable along `dim`, a coordinate of every variable that has that dimension.
    void add_coordinate(const std::string& dim, const std::string& name,
                        const std::vector<double>& values, const std::string& units,
                        const std::string& long_name) {
        put(name, Array({dim}, {values.size()}, units, long_name), &values);
        std::string& list = dim == "cell" ? cell_coordinates : channel_coordinates;
        list += (list.empty() ? "" : " ") + name;
    }
    // The array as dataset `name`, each dimension attached to its scale, chunked by incidence;
    // long_name, if given, replaces the array's own.
    h5::Handle put(const std::string& name, const Array& a,
                   const std::vector<double>* data = nullptr, const std::string& long_name = "") {
        std::vector<hsize_t> dims, chunk;
        for (size_t k = 0; k < a.rank(); ++k) {
            dims.push_back(a.shape[k]);
            chunk.push_back(a.dims[k] == "theta_i" || a.dims[k] == "phi_i" ? 1 : a.shape[k]);
        }
        const std::vector<double>& v = data ? *data : a.data;
        GONIO_CHECK_MSG(v.size() == a.count(0),
                        name + " has " + std::to_string(v.size()) + " values for its shape");
        h5::Handle d = h5::write_dataset(group, name, dims, chunk, v.data(), a.units,
                                         long_name.empty() ? a.long_name : long_name);
        std::string coordinates;
        for (size_t k = 0; k < a.rank(); ++k) {
            const auto scale = scales.find(a.dims[k]);
            GONIO_CHECK_MSG(scale != scales.end(), "no scale for dimension " + a.dims[k]);
            h5::check(H5DSattach_scale(d, scale->second, unsigned(k)),
                      ("attach " + a.dims[k] + " to " + name).c_str());
            const std::string& c = a.dims[k] == "cell"      ? cell_coordinates
                                   : a.dims[k] == "channel" ? channel_coordinates
                                                            : std::string();
            if (!c.empty() && a.rank() > 1) coordinates += (coordinates.empty() ? "" : " ") + c;
        }
        if (!coordinates.empty()) h5::write_string_attribute(d, "coordinates", coordinates);
        return d;
    }
    // A figure and its standard error beside it (name_stderr).
    void put(const std::string& name, const Estimate& e, const std::string& long_name = "") {
        put(name, e.mean, nullptr, long_name);
        put(name + "_stderr", e.error, nullptr,
            long_name.empty() ? "" : "standard error of the " + long_name);
    }
};

ResultWriter::CaseGroup ResultWriter::open_case(const CaseConfig& c, const BeckersSensor& sensor,
                                                const std::string& ndf_description) {
    using h5::Handle;
    CaseGroup g;
    Handle gcpl(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "group creation property list");
    h5::check(H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
              "H5Pset_link_creation_order");
    g.group = Handle(H5Gcreate2(file_, c.name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose,
                     ("create group " + c.name).c_str());
    const hid_t group = g.group;
    h5::write_string_attribute(group, "name", c.name);
    h5::write_string_attribute(group, "ndf", ndf_description);
    h5::write_string_attribute(group, "material", c.material.type);
    h5::write_string_attribute(group, "fresnel", c.material.description);
    h5::write_string_attribute(group, "material_source", c.material.source);
    h5::write_string_attribute(group, "masking", name_of(c.model.masking));
    h5::write_string_attribute(group, "trace_backend", c.trace.backend->name);
    h5::write_int_attribute(group, "quadrature_points", c.model.quadrature.points);
    h5::write_double_attribute(group, "quadrature_tolerance", c.model.quadrature.rel_tol);
    h5::write_int_attribute(group, "sensor_cells", sensor.cell_count());
    h5::write_string_attribute(group, "sensor", "Beckers & Beckers 2012 equal-area hemisphere");

    const size_t ncell = sensor.cell_count(), nc = c.channels();
    g.add_scale("theta_i", c.theta_i_deg, "degree", "polar angle of the incident direction i",
                false);
    g.add_scale("phi_i", c.phi_i_deg, "degree", "azimuth of the incident direction i", false);
    std::vector<double> index(ncell), channel(nc);
    for (size_t k = 0; k < ncell; ++k) index[k] = static_cast<double>(k);
    for (size_t k = 0; k < nc; ++k) channel[k] = static_cast<double>(k);
    g.add_scale("cell", index, "1", "sensor cell index", true);
    g.add_scale("channel", channel, "1",
                nc == 1 && c.material.wavelengths_nm.empty()
                    ? "spectral channel (achromatic material: one channel)"
                    : "spectral channel",
                true);
    // Cell geometry: coordinates along the cell dimension.
    auto coord = [&](const char* name, auto get, const char* units, const char* what, bool deg) {
        std::vector<double> v(ncell);
        for (size_t k = 0; k < ncell; ++k) v[k] = get(sensor.cell(static_cast<int>(k)));
        if (deg) v = to_degrees(v);
        g.add_coordinate("cell", name, v, units, what);
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
    if (!c.material.wavelengths_nm.empty())
        g.add_coordinate("channel", "wavelength", c.material.wavelengths_nm, "nm",
                         "wavelength of the channel");
    return g;
}

void ResultWriter::write_models(CaseGroup& g, const std::vector<ModelResult>& models,
                                double tolerance) {
    std::vector<std::string> names;
    for (const ModelResult& r : models) {
        names.push_back(r.name);
        const std::string m = "model_" + r.name;
        g.put(m, r.brdf);
        g.put(m + "_energy", r.energy);
        g.put(m + "_albedo", r.albedo);
        if (!r.brdf_stderr.empty()) { // a Monte Carlo model
            g.put(m + "_stderr", r.brdf_stderr, nullptr,
                  "standard error of " + m + " (batch means)");
            g.put(m + "_albedo_stderr", r.albedo_stderr, nullptr,
                  "standard error of " + m + "_albedo (batch means)");
        }
        h5::write_string_attribute(g.group, m + "_compared_with", name_of(r.compared_with));
        g.put(m + "_seconds", r.seconds);
        if (r.tolerance_reached > tolerance) // a cell ran out of quadrature pieces
            h5::write_double_attribute(g.group, m + "_tolerance_reached", r.tolerance_reached);
        if (!r.l1.empty()) { // a model that knows its single scattering
            g.put(m + "_l1", r.l1);
            g.put(m + "_l2plus", r.l2plus);
            if (!r.l2plus_stderr.empty()) g.put(m + "_l2plus_stderr", r.l2plus_stderr);
            g.put(m + "_l1_albedo", r.l1_albedo);
            g.put(m + "_l2plus_albedo", r.l2plus_albedo);
        }
        if (!r.l2_albedo.empty()) { // and a Monte Carlo one, its orders
            g.put(m + "_l2_albedo", r.l2_albedo);
            if (!g.scales.count("model_order"))
                g.add_scale("model_order", {1, 2, 3}, "1",
                            "bounce order of a model; the last one holds every order from it up",
                            true);
            g.put(m + "_order_albedo", r.order_albedo);
            g.put(m + "_order_albedo_stderr", r.order_albedo_stderr);
            if (!r.order_transmittance.empty()) {
                g.put(m + "_order_transmittance", r.order_transmittance);
                g.put(m + "_order_transmittance_stderr", r.order_transmittance_stderr);
            }
        }
    }
    h5::write_string_list_attribute(g.group, "models", names);
}

void ResultWriter::write_model_case(const CaseConfig& c, const BeckersSensor& sensor,
                                    const std::string& ndf_description,
                                    const std::vector<ModelResult>& models) {
    CaseGroup g = open_case(c, sensor, ndf_description);
    write_models(g, models, c.model.quadrature.rel_tol);
}

void ResultWriter::write_simulation_case(const CaseConfig& c, const BeckersSensor& sensor,
                                         const std::string& ndf_description,
                                         const SimulationResult& sim,
                                         const std::vector<ModelResult>& models) {
    GONIO_CHECK_MSG(sim.complete(), "the simulation of " + c.name + " is incomplete");
    CaseGroup g = open_case(c, sensor, ndf_description);
    h5::write_string_attribute(g.group, "surface", sim.surface);
    h5::write_int_attribute(g.group, "rays_per_incidence", c.trace.rays);
    h5::write_int_attribute(g.group, "max_bounces", c.trace.max_bounces);
    std::vector<double> orders(size_t(sim.orders()));
    for (size_t k = 0; k < orders.size(); ++k) orders[k] = double(k + 1);
    g.add_scale("order", orders, "1", "bounce order; the last one holds every order from it up",
                true);
    h5::write_int_attribute(g.scales["order"], "overflow_order", sim.orders());

    // One side of the sample (reflection on the upper sensor, transmission on the lower one).
    struct SideNames {
        const char *dist, *energy, *first, *higher, *all, *a1, *a2, *a2plus, *aall;
    };
    auto write_side = [&](const SideNames& n, const SimulatedSide& side) {
        g.put(n.dist, side.distribution);
        g.put(n.energy, side.order_energy);
        g.put(n.first, side.first);
        g.put(n.higher, side.higher);
        g.put(n.all, side.all);
        g.put(n.a1, side.first_albedo);
        g.put(n.a2, side.second_albedo);
        g.put(n.a2plus, side.higher_albedo);
        g.put(n.aall, side.all_albedo);
    };
    write_side({"brdf", "energy", "brdf_l1", "brdf_l2plus", "brdf_linf", "l1_albedo", "l2_albedo",
                "l2plus_albedo", "linf_albedo"},
               sim.reflected);
    if (!sim.transmitted.empty())
        write_side({"btdf", "transmitted_energy", "btdf_t1", "btdf_t2plus", "btdf_tinf",
                    "t1_albedo", "t2_albedo", "t2plus_albedo", "transmitted_albedo"},
                   sim.transmitted);
    g.put("ledger_absorbed", sim.absorbed);
    g.put("ledger_capped", sim.capped);
    g.put("ledger_lost", sim.lost);
    g.put("ledger_unaccounted", sim.unaccounted);
    g.put("rays", sim.rays);
    g.put("segments", sim.segments);
    g.put("trace_seconds", sim.seconds);
    g.put("rounds", sim.rounds);
    g.put("realisations", sim.realisations);
    h5::write_string_attribute(g.group, "error_scope", name_of(sim.error_scope));
    if (sim.error_scope == ErrorScope::rays_and_surface) {
        g.put("surface_share_l1_albedo", sim.share_l1_albedo);
        g.put("surface_share_l2plus_albedo", sim.share_l2plus_albedo);
        g.put("surface_share_linf_albedo", sim.share_linf_albedo);
        g.put("surface_share_l1_cells", sim.share_l1_cells);
        g.put("surface_share_linf_cells", sim.share_linf_cells);
    }
    g.put("achieved_error", sim.achieved_error);
    h5::write_int_attribute(g.group, "batches", c.trace.batches);
    std::vector<std::string> stops;
    for (StopReason r : sim.stop) stops.push_back(name_of(r));
    h5::write_string_list_attribute(g.group, "stop", stops);
    if (c.trace.target.active()) {
        h5::write_string_attribute(g.group, "target_quantity", name_of(c.trace.target.quantity));
        h5::write_double_attribute(g.group, "target_relative_error", c.trace.target.relative_error);
        h5::write_double_attribute(g.group, "target_cell_fraction", c.trace.target.cell_fraction);
        h5::write_double_attribute(g.group, "target_max_rays", double(c.trace.target.max_rays));
        h5::write_double_attribute(g.group, "target_max_seconds", c.trace.target.max_seconds);
    }
    write_models(g, models, c.model.quadrature.rel_tol);
    // Each model against what it models (single scattering or every order), with errors, and a
    // model of every order that knows its single scattering, its orders 2 and up against L2+.
    auto write_comparison = [&](const std::string& n, const std::string& model,
                                const std::string& what, const ComparisonArrays& cmp) {
        g.put(n + "_relative_difference", cmp.relative_difference,
              "(simulated " + what + " albedo - " + model + " albedo) / " + model + " albedo");
        g.put(n + "_sigmas", cmp.sigmas, nullptr,
              "(simulated " + what + " albedo - " + model +
                  " albedo) in standard errors of the difference");
        g.put(n + "_distance", cmp.distance,
              "sum |f_sim - f_model| Omega_perp / sum f_model Omega_perp over the cells (" + what +
                  " against " + model + ")");
        g.put(n + "_ratio", cmp.ratio,
              "simulated " + what + " / " + model +
                  " per cell (0 where the model is below 1e-12 of its peak)");
    };
    for (size_t mi = 0; mi < models.size(); ++mi) {
        const ModelResult& model = models[mi];
        const ComparisonArrays& cmp = sim.comparisons.at(mi);
        const std::string n = model.name;
        write_comparison(n, "model_" + n,
                         model.compared_with == ModelTarget::linf ? "every order" : "L1", cmp);
        if (!cmp.l2plus.empty())
            write_comparison(n + "_l2plus", "model_" + n + "_l2plus", "L2+", cmp.l2plus[0]);
    }
}

void ResultWriter::write_timings(const std::string& case_name_or_empty,
                                 const std::vector<std::pair<std::string, double>>& phase_seconds) {
    h5::Handle group;
    if (!case_name_or_empty.empty())
        group =
            h5::Handle(H5Gopen2(file_, case_name_or_empty.c_str(), H5P_DEFAULT), H5Gclose,
                       ("open group " + case_name_or_empty + " (write the case first)").c_str());
    const hid_t target = case_name_or_empty.empty() ? hid_t(file_) : hid_t(group);
    std::vector<std::string> names;
    for (const auto& [name, seconds] : phase_seconds) {
        names.push_back(name);
        h5::write_double_attribute(target, "phase_" + name + "_seconds", seconds);
    }
    h5::write_string_list_attribute(target, "phases", names);
}

void ResultWriter::commit() {
    file_.commit();
}

} // namespace gonio
