#include "gonio/cli/commands.h"
#include "gonio/io/json.h"
#include "gonio/io/result_reader.h"

#include <cstdio>
#include <sstream>
#include <string>

namespace gonio {

namespace {

std::string attribute(const std::map<std::string, std::string>& a, const std::string& k) {
    auto it = a.find(k);
    return it == a.end() ? "" : it->second;
}

std::vector<std::string> split(const std::string& list) {
    std::vector<std::string> out;
    std::stringstream in(list);
    for (std::string item; std::getline(in, item, ',');) out.push_back(item);
    return out;
}

void print_json(const ResultSummary& s) {
    std::string out = "{\n";
    out += "  \"file\": " + json::quote(s.path) + ",\n";
    for (const char* k :
         {"file_format", "gonio_version", "git_hash", "command_line", "config_path", "created_utc"})
        out += "  " + json::quote(k) + ": " + json::quote(attribute(s.attributes, k)) + ",\n";
    out += "  \"seed\": " + std::to_string(s.seed) + ",\n";
    out += "  \"cases\": [";
    for (size_t ci = 0; ci < s.cases.size(); ++ci) {
        const CaseSummary& c = s.cases[ci];
        out += ci ? ",\n    {" : "\n    {";
        out += "\"name\": " + json::quote(c.name);
        for (const char* k : {"ndf", "material", "fresnel", "masking"})
            out += ", " + json::quote(k) + ": " + json::quote(attribute(c.attributes, k));
        out += ", \"cells\": " + std::to_string(c.cells);
        out += ", \"channels\": " + std::to_string(c.channels);
        out += ", \"wavelength_nm\": " + json::array(c.wavelength_nm);
        out += ",\n     \"incidences\": [";
        const size_t np = c.phi_i_deg.size(), nc = c.channels;
        for (size_t t = 0; t < c.theta_i_deg.size(); ++t) {
            for (size_t p = 0; p < np; ++p) {
                out += (t || p) ? ",\n       {" : "\n       {";
                out += "\"theta_i\": " + json::number(c.theta_i_deg[t]);
                out += ", \"phi_i\": " + json::number(c.phi_i_deg[p]);
                for (const auto& [name, values] : c.albedos) {
                    std::vector<double> v(values.begin() + (t * np + p) * nc,
                                          values.begin() + (t * np + p + 1) * nc);
                    out += ", " + json::quote(name) + ": " + json::array(v);
                }
                for (const auto& [name, values] : c.runs)
                    out += ", " + json::quote(name) + ": " + json::number(values[t * np + p]);
                const std::vector<std::string> stops = split(attribute(c.attributes, "stop"));
                if (t * np + p < stops.size())
                    out += ", \"stop\": " + json::quote(stops[t * np + p]);
                out += "}";
            }
        }
        out += "]}";
    }
    out += "\n  ]\n}\n";
    std::fputs(out.c_str(), stdout);
}

void print_text(const ResultSummary& s) {
    std::printf("%s\n", s.path.c_str());
    std::printf("  gonio %s (git %s), seed %lld, created %s\n",
                attribute(s.attributes, "gonio_version").c_str(),
                attribute(s.attributes, "git_hash").c_str(), s.seed,
                attribute(s.attributes, "created_utc").c_str());
    std::printf("  config %s\n  command %s\n", attribute(s.attributes, "config_path").c_str(),
                attribute(s.attributes, "command_line").c_str());
    for (const CaseSummary& c : s.cases) {
        std::printf("\ncase %s: %s, %s, masking %s, %d cells, %d channel%s", c.name.c_str(),
                    attribute(c.attributes, "ndf").c_str(),
                    attribute(c.attributes, "fresnel").c_str(),
                    attribute(c.attributes, "masking").c_str(), c.cells, c.channels,
                    c.channels == 1 ? "" : "s");
        if (!c.wavelength_nm.empty()) {
            std::printf(" (");
            for (size_t k = 0; k < c.wavelength_nm.size(); ++k)
                std::printf("%s%g nm", k ? ", " : "", c.wavelength_nm[k]);
            std::printf(")");
        }
        // Each quantity with its standard error beside it, when the file has one.
        auto is_error = [](const std::string& name) {
            return name.size() > 7 && name.compare(name.size() - 7, 7, "_stderr") == 0;
        };
        const std::vector<std::string> stops = split(attribute(c.attributes, "stop"));
        const auto rays = c.runs.find("rays");
        std::printf("\n  %8s %8s", "theta_i", "phi_i");
        for (const auto& [name, v] : c.albedos)
            if (!is_error(name)) std::printf("  %s", name.c_str());
        if (rays != c.runs.end()) std::printf("  rays  stop");
        std::printf("\n");
        const size_t np = c.phi_i_deg.size(), nc = c.channels;
        for (size_t t = 0; t < c.theta_i_deg.size(); ++t)
            for (size_t p = 0; p < np; ++p) {
                std::printf("  %8.3f %8.3f", c.theta_i_deg[t], c.phi_i_deg[p]);
                for (const auto& [name, v] : c.albedos) {
                    if (is_error(name)) continue;
                    const auto err = c.albedos.find(name + "_stderr");
                    std::printf(" ");
                    for (size_t k = 0; k < nc; ++k) {
                        const size_t i = (t * np + p) * nc + k;
                        std::printf(" %.6f", v[i]);
                        if (err != c.albedos.end()) std::printf("±%.1e", err->second[i]);
                    }
                }
                if (rays != c.runs.end())
                    std::printf("  %.0f  %s", rays->second[t * np + p],
                                t * np + p < stops.size() ? stops[t * np + p].c_str() : "-");
                std::printf("\n");
            }
    }
}

} // namespace

int run_info_command(const std::string& path, bool as_json) {
    const ResultSummary s = read_result_summary(path);
    if (as_json)
        print_json(s);
    else
        print_text(s);
    return 0;
}

} // namespace gonio
