// Directional albedo per bounce order as CSV: E(theta_i) for L1, L2+ and L-infinity (and the
// transmitted albedo), each with its standard error, per incidence and channel; the table a
// renderer's multiple-scattering compensation holds (Kulla & Conty 2017, "Revisiting Physically
// Based Shading at Imageworks", SIGGRAPH course: E(mu) and E_avg = 2 integral E(mu) mu dmu), here
// from explicit microgeometry. With --sweep KEY every case of the file is written, with the
// value of KEY (a config key such as ndf.alpha) in the first column: the 2-D table E(mu, KEY).
#include "core/number_text.h"
#include "gonio/export/export_formats.h"
#include "gonio_version.h"

#include <algorithm>
#include <cmath>
#include <toml++/toml.h>

namespace gonio {

namespace {
// The value of `key` in case `index` of the effective config (the case's own, else the top
// level's), as text.
std::string config_value(const toml::table& root, size_t index, const std::string& key,
                         const std::string& case_name) {
    const toml::node* found = nullptr;
    if (const toml::array* cases = root["case"].as_array(); cases && index < cases->size())
        if (const toml::table* t = (*cases)[index].as_table()) found = t->at_path(key).node();
    if (!found) found = root.at_path(key).node();
    if (!found)
        throw ExportRefused("--sweep " + key + ": the key is not set for case " + case_name);
    if (const auto v = found->value<double>()) return shortest(*v);
    if (const auto s = found->value<std::string>()) return *s;
    throw ExportRefused("--sweep " + key + ": not a number or a string in case " + case_name);
}

// E_avg = 2 integral_0^1 E(mu) mu dmu by the trapezoid rule over the swept mu, E held constant
// to mu = 0 and mu = 1.
double average_albedo(std::vector<std::pair<double, double>> mu_e) {
    std::sort(mu_e.begin(), mu_e.end());
    mu_e.insert(mu_e.begin(), {0.0, mu_e.front().second});
    mu_e.push_back({1.0, mu_e.back().second});
    double sum = 0;
    for (size_t k = 1; k < mu_e.size(); ++k) {
        const auto& [m0, e0] = mu_e[k - 1];
        const auto& [m1, e1] = mu_e[k];
        sum += (m1 - m0) * (e0 * m0 + e1 * m1); // 2 * trapezoid of E mu
    }
    return sum;
}
} // namespace

static void write_albedo(const ResultCase& first, const ExportOptions& o, std::ostream& out,
                         ExportReport& report) {
    std::vector<ResultCase> cases;
    std::vector<std::string> sweep_values;
    if (o.sweep.empty()) {
        cases.push_back(first);
    } else {
        const auto names = read_result_case_names(first.file);
        const toml::table root = toml::parse(first.effective_toml);
        for (size_t k = 0; k < names.size(); ++k) {
            cases.push_back(read_result_case(first.file, names[k]));
            sweep_values.push_back(config_value(root, k, o.sweep, names[k]));
        }
    }
    bool any_transmits = false;
    for (const ResultCase& c : cases) {
        if (!c.simulated)
            throw ExportRefused(c.file + ": case " + c.name +
                                " holds models only (gonio model): no simulated albedos");
        any_transmits = any_transmits || c.transmits;
    }
    const char* orders[] = {"l1", "l2plus", "linf", "transmitted"};
    out << "# gonio " << kVersion << " (git " << kGitHash << "): directional albedo per bounce "
        << "order from " << first.file << "\n"
        << "# E(theta_i) = integral f cos theta_o d omega_o over the upper sensor (transmitted: "
           "the lower); *_stderr: standard errors ("
        << (first.config.surface.realisations > 1 ? "rays and surfaces" : "rays, given the surface")
        << ")\n"
        << "# average: E_avg = 2 integral E(mu) mu dmu (Kulla & Conty 2017), trapezoid over the "
           "swept mu, E constant beyond\n";
    std::string header = (o.sweep.empty() ? "" : o.sweep + ",") +
                         "case,theta_i_deg,phi_i_deg,mu_i,channel,wavelength_nm";
    for (int k = 0; k < (any_transmits ? 4 : 3); ++k)
        header += std::string(",") + orders[k] + "," + orders[k] + "_stderr";
    std::vector<std::string> rows, averages;
    for (size_t ci = 0; ci < cases.size(); ++ci) {
        const ResultCase& c = cases[ci];
        std::vector<std::vector<double>> values, errors;
        for (int k = 0; k < 4; ++k) {
            const bool present = k < 3 || c.transmits;
            const std::string name = std::string(orders[k]) + "_albedo";
            values.push_back(present ? c.read_albedo(name) : std::vector<double>{});
            errors.push_back(present ? c.read_albedo(name + "_stderr") : std::vector<double>{});
        }
        const size_t nt = c.theta_i_deg.size(), np = c.phi_i_deg.size(), C = size_t(c.channels);
        for (size_t ti = 0; ti < nt; ++ti)
            for (size_t pj = 0; pj < np; ++pj)
                for (size_t ch = 0; ch < C; ++ch) {
                    const size_t at = (ti * np + pj) * C + ch;
                    std::string row =
                        (o.sweep.empty() ? "" : sweep_values[ci] + ",") + c.name + "," +
                        shortest(c.theta_i_deg[ti]) + "," + shortest(c.phi_i_deg[pj]) + "," +
                        shortest(std::cos(radians(c.theta_i_deg[ti]))) + "," + std::to_string(ch) +
                        "," + (c.wavelength_nm.empty() ? "" : shortest(c.wavelength_nm[ch]));
                    for (int k = 0; k < (any_transmits ? 4 : 3); ++k) {
                        if (values[k].empty())
                            row += ",nan,nan";
                        else
                            row += "," + shortest(values[k][at]) + "," + shortest(errors[k][at]);
                    }
                    rows.push_back(std::move(row));
                }
        for (size_t pj = 0; pj < np; ++pj)
            for (size_t ch = 0; ch < C; ++ch) {
                std::string line = "# average " + c.name + " phi_i " + shortest(c.phi_i_deg[pj]) +
                                   " channel " + std::to_string(ch) + ":";
                for (int k = 0; k < (c.transmits ? 4 : 3); ++k) {
                    std::vector<std::pair<double, double>> mu_e;
                    for (size_t ti = 0; ti < nt; ++ti)
                        mu_e.emplace_back(std::cos(radians(c.theta_i_deg[ti])),
                                          values[k][(ti * np + pj) * C + ch]);
                    line += std::string(" ") + orders[k] + " " + shortest(average_albedo(mu_e));
                }
                averages.push_back(line);
            }
        if (nt < 8)
            report.notes.push_back("case " + c.name + ": E_avg from only " + std::to_string(nt) +
                                   " incidences");
    }
    for (const std::string& a : averages) out << a << "\n";
    out << header << "\n";
    for (const std::string& r : rows) out << r << "\n";
    report.notes.push_back(std::to_string(rows.size()) + " rows from " +
                           std::to_string(cases.size()) + " case(s)");
}

const ExportFormat& albedo_format() {
    static const ExportFormat f{"albedo", "directional albedo per order, E(theta_i), as CSV",
                                false,    false,
                                true,     write_albedo};
    return f;
}

} // namespace gonio
