#include "gonio/table/result_case.h"

#include "gonio/io/hdf5_handles.h"
#include "gonio/io/result_reader.h"
#include "heightfield/surface_generator.h"

#include <cmath>
#include <stdexcept>

namespace gonio {

bool case_is_isotropic(const CaseConfig& c) {
    // A measured map, or a generator whose facets follow a shape rather than the NDF.
    if (!c.surface.generator || !c.surface.generator->follows_ndf(c.surface)) return false;
    return c.ndf->isotropic();
}

ResultCase read_result_case(const std::string& file, const std::string& name) {
    const ResultSummary summary = read_result_summary(file);
    if (summary.cases.empty()) throw std::runtime_error(file + ": holds no case");
    const CaseSummary* found = nullptr;
    std::string names;
    for (const CaseSummary& c : summary.cases) {
        names += (names.empty() ? "" : ", ") + c.name;
        if (c.name == name) found = &c;
    }
    if (name.empty()) {
        if (summary.cases.size() > 1)
            throw std::runtime_error(file + " holds " + std::to_string(summary.cases.size()) +
                                     " cases (" + names + "): choose one with --case");
        found = &summary.cases.front();
    }
    if (!found)
        throw std::runtime_error(file + ": no case named '" + name + "' (it holds " + names + ")");

    ResultCase r;
    r.file = file;
    r.name = found->name;
    r.theta_i_deg = found->theta_i_deg;
    r.phi_i_deg = found->phi_i_deg;
    r.wavelength_nm = found->wavelength_nm;
    r.cells = found->cells;
    r.channels = found->channels;
    if (auto m = found->attributes.find("material"); m != found->attributes.end())
        r.material = m->second;
    const auto effective = summary.attributes.find("config_effective_toml");
    if (effective == summary.attributes.end())
        throw std::runtime_error(file + ": no config_effective_toml attribute to re-read the case");
    const auto config_path = summary.attributes.find("config_path");
    r.effective_toml = effective->second;
    Config cfg;
    try {
        // Under its own path: a lone case is named after the config file's stem (and renamed
        // after its group below), whatever the result file is called.
        cfg = parse_config(effective->second, config_path != summary.attributes.end()
                                                  ? config_path->second
                                                  : std::string("config.toml"));
    } catch (const std::exception& e) {
        throw std::runtime_error(file + ": cannot re-read the config it stores: " + e.what());
    }
    // The file's groups are the config's cases in order (a lone unnamed case is named after the
    // config file, which the stored text does not carry).
    const size_t index = size_t(found - summary.cases.data());
    if (cfg.cases.size() != summary.cases.size())
        throw std::runtime_error(file + ": its stored config has " +
                                 std::to_string(cfg.cases.size()) + " cases, the file " +
                                 std::to_string(summary.cases.size()));
    r.config = std::move(cfg.cases[index]);
    r.config.name = r.name;
    r.simulated = r.has("brdf_linf");
    r.transmits = r.has("btdf_tinf");
    r.isotropic = case_is_isotropic(r.config);
    return r;
}

std::vector<std::string> read_result_case_names(const std::string& file) {
    std::vector<std::string> names;
    for (const CaseSummary& c : read_result_summary(file).cases) names.push_back(c.name);
    if (names.empty()) throw std::runtime_error(file + ": holds no case");
    return names;
}

namespace {
h5::Handle open_group(const std::string& file, const std::string& name, h5::Handle& f) {
    h5::silence_errors();
    f = h5::Handle(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                   ("open " + file).c_str());
    return h5::Handle(H5Gopen2(f, name.c_str(), H5P_DEFAULT), H5Gclose,
                      ("open group " + name + " of " + file).c_str());
}
} // namespace

bool ResultCase::has(const std::string& dataset) const {
    h5::Handle f;
    const h5::Handle g = open_group(file, name, f);
    return H5Lexists(g, dataset.c_str(), H5P_DEFAULT) > 0;
}

namespace {
std::vector<double> read_checked(const ResultCase& c, const std::string& dataset,
                                 const std::vector<hsize_t>& shape) {
    h5::Handle f;
    const h5::Handle g = open_group(c.file, c.name, f);
    const std::string where = c.file + ": case " + c.name + ": ";
    if (H5Lexists(g, dataset.c_str(), H5P_DEFAULT) <= 0)
        throw std::runtime_error(where + "no dataset " + dataset);
    std::vector<hsize_t> dims;
    std::vector<double> v = h5::read_doubles(g, dataset, &dims);
    if (dims != shape) {
        std::string got, want;
        for (hsize_t d : dims) got += (got.empty() ? "" : " x ") + std::to_string(d);
        for (hsize_t d : shape) want += (want.empty() ? "" : " x ") + std::to_string(d);
        throw std::runtime_error(where + dataset + ": shaped " + got + ", the case's axes give " +
                                 want);
    }
    for (double x : v)
        if (!std::isfinite(x) || x < 0)
            throw std::runtime_error(where + dataset + ": holds " + std::to_string(x) +
                                     " (a BRDF, an albedo or an error is finite and not "
                                     "negative)");
    return v;
}
} // namespace

std::vector<double> ResultCase::read_map(const std::string& dataset) const {
    return read_checked(*this, dataset,
                        {theta_i_deg.size(), phi_i_deg.size(), hsize_t(cells), hsize_t(channels)});
}

std::vector<double> ResultCase::read_albedo(const std::string& dataset) const {
    return read_checked(*this, dataset, {theta_i_deg.size(), phi_i_deg.size(), hsize_t(channels)});
}

} // namespace gonio
