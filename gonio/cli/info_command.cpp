#include "gonio/cli/command.h"
#include "gonio/io/result_reader.h"
#include "gonio/io/simulation_result.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

namespace gonio {

namespace {

// What a case's standard errors include.
std::string scope_text(const CaseSummary& c) {
    if (enum_named<ErrorScope>(c.attributes.at("error_scope")) == ErrorScope::rays_and_surface) {
        double most = 0;
        if (auto r = c.runs.find("realisations"); r != c.runs.end())
            for (double v : r->second) most = std::max(most, v);
        return "rays+surface (up to " + std::to_string(int(most)) +
               " independent surfaces: the error of the NDF's BSDF)";
    }
    return "rays (one surface: conditional on it; surface.realisations >= 2 includes the "
           "surfaces' spread)";
}

std::string attribute(const std::map<std::string, std::string>& a, const std::string& k) {
    auto it = a.find(k);
    return it == a.end() ? "" : it->second;
}

// Phase -> seconds, in the order the phases ran.
nlohmann::ordered_json timings_json(const std::vector<std::pair<std::string, double>>& timings) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    for (const auto& [phase, seconds] : timings) out[phase] = seconds;
    return out;
}

void print_json(const ResultSummary& s) {
    using json = nlohmann::ordered_json;
    json out = json::object();
    out["file"] = s.path;
    for (const char* k :
         {"file_format", "gonio_version", "git_hash", "command_line", "config_path", "created_utc"})
        out[k] = attribute(s.attributes, k);
    out["seed"] = s.seed;
    json how = json::object(); // how it ran: processes, threads, shard, merged parts
    for (const char* k : {"mpi_ranks", "threads_per_rank", "shard", "merged_parts",
                          "memory_estimate_bytes", "memory_peak_bytes"})
        if (s.attributes.count(k)) how[k] = attribute(s.attributes, k);
    if (!how.empty()) out["execution"] = how;
    if (!s.timings.empty()) out["timings"] = timings_json(s.timings);
    json cases = json::array();
    for (const CaseSummary& c : s.cases) {
        json jc = json::object();
        jc["name"] = c.name;
        for (const char* k : {"ndf", "material", "fresnel", "masking", "trace_backend"})
            jc[k] = attribute(c.attributes, k);
        jc["cells"] = c.cells;
        jc["channels"] = c.channels;
        jc["wavelength_nm"] = c.wavelength_nm;
        jc["models"] = c.models;
        if (c.attributes.count("error_scope")) // simulated cases, format 2
            jc["error_scope"] = attribute(c.attributes, "error_scope");
        if (!c.timings.empty()) jc["timings"] = timings_json(c.timings);
        json incidences = json::array();
        const size_t np = c.phi_i_deg.size(), nc = c.channels;
        for (size_t t = 0; t < c.theta_i_deg.size(); ++t) {
            for (size_t p = 0; p < np; ++p) {
                const size_t i = t * np + p;
                json ji = json::object();
                ji["theta_i"] = c.theta_i_deg[t];
                ji["phi_i"] = c.phi_i_deg[p];
                for (const auto& [name, values] : c.albedos)
                    ji[name] = std::vector<double>(values.begin() + long(i * nc),
                                                   values.begin() + long((i + 1) * nc));
                for (const auto& [name, values] : c.runs) ji[name] = values[i];
                if (i < c.stop.size()) ji["stop"] = c.stop[i];
                incidences.push_back(std::move(ji));
            }
        }
        jc["incidences"] = std::move(incidences);
        cases.push_back(std::move(jc));
    }
    out["cases"] = std::move(cases);
    // Numbers in their shortest round-trip form, NaN and infinities as null; a string that is not
    // UTF-8 (a config file's bytes) gets U+FFFD where it is broken rather than failing.
    const std::string text = out.dump(2, ' ', false, json::error_handler_t::replace);
    std::fputs((text + "\n").c_str(), stdout);
}

void print_text(const ResultSummary& s) {
    std::printf("%s\n", s.path.c_str());
    std::printf("  gonio %s (git %s), seed %lld, created %s\n",
                attribute(s.attributes, "gonio_version").c_str(),
                attribute(s.attributes, "git_hash").c_str(), s.seed,
                attribute(s.attributes, "created_utc").c_str());
    std::printf("  config %s\n  command %s\n", attribute(s.attributes, "config_path").c_str(),
                attribute(s.attributes, "command_line").c_str());
    if (s.attributes.count("mpi_ranks"))
        std::printf(
            "  ran on %s process(es) x %s thread(s)%s\n",
            attribute(s.attributes, "mpi_ranks").c_str(),
            attribute(s.attributes, "threads_per_rank").c_str(),
            s.attributes.count("merged_parts")
                ? (", merged from " + attribute(s.attributes, "merged_parts") + " parts").c_str()
                : "");
    if (s.attributes.count("memory_peak_bytes"))
        std::printf("  memory %.0f MB at its peak (estimated %.0f MB before the run)\n",
                    std::atof(attribute(s.attributes, "memory_peak_bytes").c_str()) / 1e6,
                    std::atof(attribute(s.attributes, "memory_estimate_bytes").c_str()) / 1e6);
    auto print_timings = [](const char* indent,
                            const std::vector<std::pair<std::string, double>>& timings) {
        if (timings.empty()) return;
        std::printf("%stimings", indent);
        for (const auto& [phase, seconds] : timings)
            std::printf(" %s %.3f s", phase.c_str(), seconds);
        std::printf("\n");
    };
    print_timings("  ", s.timings);
    for (const CaseSummary& c : s.cases) {
        const std::string backend = attribute(c.attributes, "trace_backend");
        std::printf("\ncase %s: %s, %s, masking %s, traced by %s, %d cells, %d channel%s",
                    c.name.c_str(), attribute(c.attributes, "ndf").c_str(),
                    attribute(c.attributes, "fresnel").c_str(),
                    attribute(c.attributes, "masking").c_str(),
                    backend.empty() ? "embree (a file older than the attribute)" : backend.c_str(),
                    c.cells, c.channels, c.channels == 1 ? "" : "s");
        if (!c.wavelength_nm.empty()) {
            std::printf(" (");
            for (size_t k = 0; k < c.wavelength_nm.size(); ++k)
                std::printf("%s%g nm", k ? ", " : "", c.wavelength_nm[k]);
            std::printf(")");
        }
        if (c.attributes.count("error_scope"))
            std::printf("\n  standard errors: %s", scope_text(c).c_str());
        // Each quantity with its standard error beside it, when the file has one.
        auto is_error = [](const std::string& name) {
            return name.size() > 7 && name.compare(name.size() - 7, 7, "_stderr") == 0;
        };
        const std::vector<std::string>& stops = c.stop;
        const auto rays = c.runs.find("rays");
        std::printf("\n");
        print_timings("  ", c.timings);
        std::printf("  %8s %8s", "theta_i", "phi_i");
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

namespace {
std::function<int()> setup(CLI::App& app, const CliContext&) {
    auto path = std::make_shared<std::string>();
    auto json = std::make_shared<bool>(false);
    app.add_option("file", *path, "HDF5 result file")->required();
    app.add_flag("--json", *json, "Print a JSON object instead of text");
    return [path, json] {
        const ResultSummary s = read_result_summary(*path);
        *json ? print_json(s) : print_text(s);
        return 0;
    };
}
} // namespace

const Command& info_command() {
    static const Command c{"info", "Summarise a result file", setup};
    return c;
}

} // namespace gonio
