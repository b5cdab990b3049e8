#include "gonio/io/result_writer.h"

#include "gonio_version.h"

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <hdf5_hl.h>
#include <stdexcept>
#include <tuple>
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

// A case's group with its coordinate scales, ready for datasets to attach them.
struct ResultWriter::CaseGroup {
    h5::Handle group, theta_i, phi_i, cell, channel, order;
    std::vector<h5::Handle> cell_coords, channel_coords;
    size_t nt = 0, np = 0, ncell = 0, nc = 0;

    void attach_incidence(hid_t ds) {
        h5::check(H5DSattach_scale(ds, theta_i, 0), "attach theta_i");
        h5::check(H5DSattach_scale(ds, phi_i, 1), "attach phi_i");
    }
    void attach_cells(hid_t ds, unsigned dim) {
        h5::check(H5DSattach_scale(ds, cell, dim), "attach cell");
        for (auto& h : cell_coords)
            h5::check(H5DSattach_scale(ds, h, dim), "attach cell coordinate");
    }
    void attach_channels(hid_t ds, unsigned dim) {
        h5::check(H5DSattach_scale(ds, channel, dim), "attach channel");
        for (auto& h : channel_coords) h5::check(H5DSattach_scale(ds, h, dim), "attach wavelength");
    }
    // [theta_i, phi_i, channel] per-incidence values.
    void per_incidence(const std::string& name, const std::vector<double>& v,
                       const std::string& units, const std::string& what) {
        h5::Handle d =
            h5::write_dataset(group, name, {nt, np, nc}, {1, 1, nc}, v.data(), units, what);
        attach_incidence(d);
        attach_channels(d, 2);
    }
    // [theta_i, phi_i, cell, channel] maps.
    void per_cell(const std::string& name, const std::vector<double>& v, const std::string& units,
                  const std::string& what) {
        h5::Handle d = h5::write_dataset(group, name, {nt, np, ncell, nc}, {1, 1, ncell, nc},
                                         v.data(), units, what);
        attach_incidence(d);
        attach_cells(d, 2);
        attach_channels(d, 3);
    }
};

ResultWriter::CaseGroup ResultWriter::open_case(const CaseConfig& c, const std::string& ndf_description,
                                              const BeckersSensor& sensor) {
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
    h5::write_string_attribute(group, "masking", masking_name(c.model.masking));
    h5::write_int_attribute(group, "quadrature_points", c.model.quadrature.points);
    h5::write_double_attribute(group, "quadrature_tolerance", c.model.quadrature.rel_tol);
    h5::write_int_attribute(group, "sensor_cells", sensor.cell_count());
    h5::write_string_attribute(group, "sensor", "Beckers & Beckers 2012 equal-area hemisphere");

    g.nt = c.theta_i_deg.size(), g.np = c.phi_i_deg.size();
    g.ncell = sensor.cell_count(), g.nc = c.channels();
    g.theta_i = h5::write_scale(group, "theta_i", c.theta_i_deg, "degree",
                                "polar angle of the incident direction i");
    g.phi_i = h5::write_scale(group, "phi_i", c.phi_i_deg, "degree",
                              "azimuth of the incident direction i");
    std::vector<double> index(g.ncell), channel(g.nc);
    for (size_t k = 0; k < g.ncell; ++k) index[k] = static_cast<double>(k);
    for (size_t k = 0; k < g.nc; ++k) channel[k] = static_cast<double>(k);
    g.cell = h5::write_scale(group, "cell", index, "", "sensor cell index", true);
    g.channel = h5::write_scale(group, "channel", channel, "",
                                g.nc == 1 && c.material.wavelengths_nm.empty()
                                    ? "spectral channel (achromatic material: one channel)"
                                    : "spectral channel",
                                true);
    // Cell geometry: every coordinate is a dimension scale of the cell dimension.
    auto coord = [&](const char* name, auto get, const char* units, const char* what, bool deg) {
        std::vector<double> v(g.ncell);
        for (size_t k = 0; k < g.ncell; ++k) v[k] = get(sensor.cell(static_cast<int>(k)));
        if (deg) v = to_degrees(v);
        g.cell_coords.push_back(h5::write_scale(group, name, v, units, what));
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
        g.channel_coords.push_back(h5::write_scale(group, "wavelength", c.material.wavelengths_nm, "nm",
                                                   "wavelength of the channel"));
    return g;
}

void ResultWriter::write_models(CaseGroup& g, const BeckersSensor& sensor,
                                const std::vector<ModelResult>& models) {
    std::string names;
    for (const ModelResult& r : models) {
        names += (names.empty() ? "" : ",") + r.name;
        const std::string m = "model_" + r.name;
        auto brdf_of = [&](const std::vector<double>& energy) {
            std::vector<double> brdf(energy.size());
            for (size_t k = 0; k < brdf.size(); ++k)
                brdf[k] = energy[k] /
                          sensor.cell(static_cast<int>((k / g.nc) % g.ncell)).projected_solid_angle;
            return brdf;
        };
        g.per_cell(m, brdf_of(r.energy), "1/sr", r.description + ": cell averages");
        g.per_cell(m + "_energy", r.energy, "1",
                   r.description + ": fraction of the incident power");
        g.per_incidence(m + "_albedo", r.albedo, "1", r.description + ": directional albedo");
        if (!r.energy_stderr.empty()) { // a Monte Carlo model
            g.per_cell(m + "_stderr", brdf_of(r.energy_stderr), "1/sr",
                       "standard error of " + m + " (batch means)");
            g.per_incidence(m + "_albedo_stderr", r.albedo_stderr, "1",
                            "standard error of " + m + "_albedo (batch means)");
        }
        h5::write_string_attribute(g.group, m + "_compared_with", r.compared_with);
        h5::Handle t = h5::write_dataset(g.group, m + "_seconds", {g.nt, g.np}, {1, 1},
                                         r.seconds.data(), "s", "wall time of the evaluation");
        g.attach_incidence(t);
        if (!r.first_energy.empty()) { // the V-cavity's orders
            g.per_cell(m + "_l1", brdf_of(r.first_energy), "1/sr",
                       "single scattering in V-cavities");
            g.per_incidence(m + "_l1_albedo", r.l1_albedo, "1", "single-scattering albedo");
            g.per_incidence(m + "_l2_albedo", r.l2_albedo, "1", "second-order albedo");
            g.per_incidence(m + "_l2plus_albedo", r.l2plus_albedo, "1",
                            "multiple-scattering albedo");
        }
    }
    h5::write_string_attribute(g.group, "models", names);
}

void ResultWriter::write_model_case(const CaseConfig& c, const std::string& ndf_description,
                                    const BeckersSensor& sensor,
                                    const std::vector<ModelResult>& models) {
    CaseGroup g = open_case(c, ndf_description, sensor);
    write_models(g, sensor, models);
}

void ResultWriter::write_simulation_case(const CaseConfig& c, const std::string& ndf_description,
                                         const BeckersSensor& sensor,
                                         const SimulationResult& sim,
                                         const std::vector<ModelResult>& models) {
    CaseGroup g = open_case(c, ndf_description, sensor);
    h5::write_string_attribute(g.group, "surface", sim.surface);
    h5::write_int_attribute(g.group, "rays_per_incidence", c.trace.rays);
    h5::write_int_attribute(g.group, "max_bounces", c.trace.max_bounces);
    const size_t no = size_t(sim.orders), nt = g.nt, np = g.np, ncell = g.ncell, nc = g.nc;
    std::vector<double> orders(no);
    for (size_t k = 0; k < no; ++k) orders[k] = double(k + 1);
    g.order = h5::write_scale(g.group, "order", orders, "",
                              "bounce order; the last one holds every order from it up", true);
    h5::write_int_attribute(g.order, "overflow_order", static_cast<long long>(no));

    const size_t maps = nt * np;
    auto brdf_of = [&](std::vector<double> v) {
        for (size_t k = 0; k < v.size(); ++k)
            v[k] /= sensor.cell(static_cast<int>((k / nc) % ncell)).projected_solid_angle;
        return v;
    };
    // One side of the sample (reflection on the upper sensor, transmission on the lower one): the
    // distribution per order (energy over the cell's projected solid angle, the same for a cell
    // and its mirror image), the first order, the higher orders and all orders, and their albedos,
    // each with its standard error.
    struct SideNames {
        const char *dist, *energy, *first, *higher, *all, *a1, *a2, *a2plus, *aall, *what;
    };
    auto write_side = [&](const SideNames& n, const SimulatedSide& side) {
        const std::string what = n.what;
        for (bool err : {false, true}) {
            const std::string suffix = err ? "_stderr" : "";
            const std::string about = err ? "standard error of the " : "";
            const std::vector<double> dist = brdf_of(err ? side.energy_stderr : side.energy);
            h5::Handle d = h5::write_dataset(
                g.group, n.dist + suffix, {nt, np, no, ncell, nc}, {1, 1, no, ncell, nc},
                dist.data(), "1/sr", about + "simulated " + what + " per bounce order, cells");
            g.attach_incidence(d);
            h5::check(H5DSattach_scale(d, g.order, 2), "attach order");
            g.attach_cells(d, 3);
            g.attach_channels(d, 4);
            h5::Handle e = h5::write_dataset(
                g.group, n.energy + suffix, {nt, np, no, nc}, {1, 1, no, nc},
                (err ? side.order_energy_stderr : side.order_energy).data(), "1",
                about + "fraction of the incident power per bounce order (" + what + ")");
            g.attach_incidence(e);
            h5::check(H5DSattach_scale(e, g.order, 2), "attach order");
            g.attach_channels(e, 3);
        }
        const std::vector<double> dist = brdf_of(side.energy),
                                  dist_err = brdf_of(side.energy_stderr);
        std::vector<double> first(maps * ncell * nc), first_err(maps * ncell * nc),
            all(maps * ncell * nc, 0.0), higher(maps * ncell * nc);
        std::vector<double> a1(maps * nc), a2(maps * nc), aall(maps * nc, 0.0),
            a2plus(maps * nc, 0.0), a1_err(maps * nc), a2_err(maps * nc);
        for (size_t m = 0; m < maps; ++m)
            for (size_t o = 0; o < no; ++o)
                for (size_t c2 = 0; c2 < ncell * nc; ++c2) {
                    const size_t i = (m * no + o) * ncell * nc + c2;
                    if (o == 0) first[m * ncell * nc + c2] = dist[i];
                    if (o == 0) first_err[m * ncell * nc + c2] = dist_err[i];
                    all[m * ncell * nc + c2] += dist[i];
                }
        for (size_t k = 0; k < first.size(); ++k) higher[k] = all[k] - first[k];
        for (size_t m = 0; m < maps; ++m)
            for (size_t o = 0; o < no; ++o)
                for (size_t k = 0; k < nc; ++k) {
                    const size_t i = (m * no + o) * nc + k;
                    const double v = side.order_energy[i];
                    aall[m * nc + k] += v;
                    if (o == 0)
                        a1[m * nc + k] = v, a1_err[m * nc + k] = side.order_energy_stderr[i];
                    if (o == 1)
                        a2[m * nc + k] = v, a2_err[m * nc + k] = side.order_energy_stderr[i];
                    if (o >= 1) a2plus[m * nc + k] += v;
                }
        auto with_error = [&](auto write, const std::string& name, const std::vector<double>& v,
                              const std::vector<double>& err, const char* units,
                              const std::string& about) {
            (g.*write)(name, v, units, about);
            (g.*write)(name + "_stderr", err, units, "standard error of the " + about);
        };
        with_error(&CaseGroup::per_cell, n.first, first, first_err, "1/sr",
                   "simulated single-bounce " + what);
        with_error(&CaseGroup::per_cell, n.higher, higher, brdf_of(side.higher_stderr), "1/sr",
                   "simulated multiple-bounce " + what);
        with_error(&CaseGroup::per_cell, n.all, all, brdf_of(side.all_stderr), "1/sr",
                   "simulated " + what + ", all orders");
        with_error(&CaseGroup::per_incidence, n.a1, a1, a1_err, "1",
                   "simulated single-bounce albedo (" + what + ")");
        with_error(&CaseGroup::per_incidence, n.a2, a2, a2_err, "1",
                   "simulated second-order albedo (" + what + ")");
        with_error(&CaseGroup::per_incidence, n.a2plus, a2plus, side.higher_albedo_stderr, "1",
                   "simulated multiple-bounce albedo (" + what + ")");
        with_error(&CaseGroup::per_incidence, n.aall, aall, side.all_albedo_stderr, "1",
                   "simulated albedo, all orders (" + what + ")");
    };
    write_side({"brdf", "energy", "brdf_l1", "brdf_l2plus", "brdf_linf", "l1_albedo", "l2_albedo",
                "l2plus_albedo", "linf_albedo", "BRDF"},
               sim.reflected);
    if (!sim.transmitted.empty())
        write_side({"btdf", "transmitted_energy", "btdf_t1", "btdf_t2plus", "btdf_tinf",
                    "t1_albedo", "t2_albedo", "t2plus_albedo", "transmitted_albedo",
                    "BTDF, lower sensor (cell k mirrors upper cell k)"},
                   sim.transmitted);
    g.per_incidence("ledger_absorbed", sim.absorbed, "1", "absorbed by the facets");
    g.per_incidence("ledger_capped", sim.capped, "1", "cut by the bounce cap");
    g.per_incidence("ledger_lost", sim.lost, "1", "lost (crack or endless ray): should be 0");
    g.per_incidence("ledger_absorbed_stderr", sim.absorbed_stderr, "1",
                    "standard error of ledger_absorbed");
    g.per_incidence("ledger_capped_stderr", sim.capped_stderr, "1",
                    "standard error of ledger_capped");
    g.per_incidence("ledger_lost_stderr", sim.lost_stderr, "1", "standard error of ledger_lost");
    g.per_incidence("ledger_unaccounted", sim.unaccounted, "1",
                    "1 - (reflected + transmitted + absorbed + capped + lost): zero to round-off");
    for (auto [name, v, units, what] :
         {std::tuple<const char*, const std::vector<double>*, const char*, const char*>{
              "rays", &sim.rays, "", "rays traced"},
          {"segments", &sim.segments, "", "ray segments (rtcIntersect1 calls)"},
          {"trace_seconds", &sim.seconds, "s", "wall time of the tracing"},
          {"rounds", &sim.rounds, "", "rounds of rays given to every batch"},
          {"achieved_error", &sim.achieved_error, "1",
           "the accuracy target's relative standard error when the run stopped (-1: no target)"}}) {
        h5::Handle d = h5::write_dataset(g.group, name, {nt, np}, {1, 1}, v->data(), units, what);
        g.attach_incidence(d);
    }
    h5::write_int_attribute(g.group, "batches", c.trace.batches);
    std::string stops;
    for (const std::string& s : sim.stop) stops += (stops.empty() ? "" : ",") + s;
    h5::write_string_attribute(g.group, "stop", stops);
    if (c.trace.target.active()) {
        h5::write_string_attribute(g.group, "target_quantity", name_of(c.trace.target.quantity));
        h5::write_double_attribute(g.group, "target_relative_error", c.trace.target.relative_error);
        h5::write_double_attribute(g.group, "target_cell_fraction", c.trace.target.cell_fraction);
        h5::write_double_attribute(g.group, "target_max_rays", double(c.trace.target.max_rays));
        h5::write_double_attribute(g.group, "target_max_seconds", c.trace.target.max_seconds);
    }
    write_models(g, sensor, models);
    // Each model against what it models (single scattering or every order), with errors.
    for (size_t mi = 0; mi < models.size(); ++mi) {
        const ModelResult& model = models[mi];
        const Comparison& cmp = sim.comparisons[mi];
        const std::string what = model.compared_with == "linf" ? "every order" : "L1";
        const std::string n = model.name;
        g.per_incidence(n + "_relative_difference", cmp.relative_difference, "1",
                        "(simulated " + what + " albedo - model_" + n + " albedo) / model_" + n +
                            " albedo");
        g.per_incidence(n + "_relative_difference_stderr", cmp.relative_difference_stderr, "1",
                        "standard error of " + n + "_relative_difference");
        g.per_incidence(n + "_sigmas", cmp.sigmas, "1",
                        "(simulated " + what + " albedo - model_" + n +
                            " albedo) in standard errors of the difference");
        g.per_incidence(
            n + "_distance", cmp.distance, "1",
            "sum |f_sim - f_model| Omega_perp / sum f_model Omega_perp over the cells (" + what +
                " against model_" + n + ")");
        g.per_incidence(n + "_distance_stderr", cmp.distance_stderr, "1",
                        "standard error of " + n + "_distance (jackknife over the batches)");
        g.per_cell(n + "_ratio", cmp.ratio, "1",
                   "simulated " + what + " / model_" + n +
                       " per cell (0 where the model is below 1e-12 of its peak)");
        g.per_cell(n + "_ratio_stderr", cmp.ratio_stderr, "1", "standard error of " + n + "_ratio");
    }
}

void ResultWriter::write_timings(const std::string& case_name,
                                 const std::vector<std::pair<std::string, double>>& phases) {
    h5::Handle group;
    hid_t where = file_;
    if (!case_name.empty()) {
        group = h5::Handle(H5Gopen2(file_, case_name.c_str(), H5P_DEFAULT), H5Gclose,
                           ("open group " + case_name).c_str());
        where = group;
    }
    std::string names;
    for (const auto& [name, seconds] : phases) {
        h5::write_double_attribute(where, "phase_" + name + "_seconds", seconds);
        names += (names.empty() ? "" : ",") + name;
    }
    h5::write_string_attribute(where, "phases", names);
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
