#include "gonio/cli/command.h"
#include "gonio/io/result_reader.h"
#include "gonio/io/simulation_result.h"
#include "gonio/model/cell_model.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace gonio {

namespace {
// With the decomposition models (gonio/masking/surface_point_model.cpp), each step's share of
// simulated L1 - Model L1 with its standard error (the two sides' errors combined: the models share
// their facet points, so this is conservative), and what is left.
void print_decomposition(const ResultSummary& s) {
    const std::vector<std::string> chain{"l1", "smith_measured_ndf", "measured_g1", "measured"};
    bool header = false;
    for (const CaseSummary& c : s.cases) {
        bool all = c.albedos.count("l1_albedo") > 0;
        for (const std::string& m : chain) all = all && c.albedos.count("model_" + m + "_albedo");
        if (!all) continue;
        if (!header)
            std::printf(
                "\nSimulated L1 - Model L1, step by step: the NDF's fidelity (Smith with the "
                "surface's D_s), the facet dependence of masking (measured G1(i,m) G1(o,m)), "
                "the correlation of masking with shadowing (measured joint G2), what is left\n"
                "%-20s %7s %7s %3s %18s %18s %18s %18s %18s\n",
                "case", "theta_i", "phi_i", "ch", "gap", "NDF fidelity", "G1 of m", "correlation",
                "left");
        header = true;
        auto at = [&](const std::string& name, size_t i) {
            const auto it = c.albedos.find(name);
            return it == c.albedos.end() ? 0.0 : it->second[i];
        };
        auto cell = [](double v, double e) {
            char text[48];
            std::snprintf(text, sizeof text, "%+.5f±%.1e", v, e);
            std::printf(" %18s", text);
        };
        const size_t np = c.phi_i_deg.size(), nc = size_t(c.channels);
        for (size_t i = 0; i < c.theta_i_deg.size() * np * nc; ++i) {
            const size_t t = i / (np * nc), p = (i / nc) % np;
            std::printf("%-20s %7.2f %7.2f %3zu", c.name.c_str(), c.theta_i_deg[t], c.phi_i_deg[p],
                        i % nc);
            const double sim = at("l1_albedo", i), sim_e = at("l1_albedo_stderr", i);
            cell(sim - at("model_l1_albedo", i), sim_e);
            for (size_t k = 1; k < chain.size(); ++k) {
                const std::string a = "model_" + chain[k - 1], b = "model_" + chain[k];
                cell(at(b + "_albedo", i) - at(a + "_albedo", i),
                     std::hypot(at(a + "_albedo_stderr", i), at(b + "_albedo_stderr", i)));
            }
            cell(sim - at("model_measured_albedo", i),
                 std::hypot(sim_e, at("model_measured_albedo_stderr", i)));
            std::printf("\n");
        }
    }
}

// The models of every order that know their single scattering (heitz16, kulla_conty, turquin,
// vcavity), order by order: each one's L1, L2+ and L-infinity albedos beside the simulated ones,
// and its L2+ against simulated L2+ (relative difference, sigmas, per-cell distance).
void print_orders(const ResultSummary& s) {
    bool header = false;
    for (const CaseSummary& c : s.cases) {
        std::vector<std::string> models;
        for (const std::string& m : c.models)
            if (c.albedos.count(m + "_l2plus_relative_difference")) models.push_back(m);
        if (models.empty() || c.albedos.count("l1_albedo") == 0) continue;
        if (!header)
            std::printf("\nMultiple scattering, order by order: each model of every order against "
                        "the simulated orders (its L2+ held against simulated L2+)\n"
                        "%-20s %7s %7s %3s %-11s %18s %18s %18s %18s %18s %7s %18s\n",
                        "case", "theta_i", "phi_i", "ch", "model", "model_L1", "model_L2+",
                        "sim_L2+", "model_Linf", "L2+_rel_diff", "sigmas", "L2+_distance");
        header = true;
        auto get = [&](const std::string& name, size_t i) {
            auto it = c.albedos.find(name);
            return it == c.albedos.end() ? -1.0 : it->second[i];
        };
        auto pm = [&](const std::string& name, size_t i, const char* format) {
            char v[64], e[32] = "";
            std::snprintf(v, sizeof v, format, get(name, i));
            if (c.albedos.count(name + "_stderr"))
                std::snprintf(e, sizeof e, "±%.1e", get(name + "_stderr", i));
            std::printf(" %18s", (std::string(v) + e).c_str());
        };
        const size_t np = c.phi_i_deg.size(), nc = size_t(c.channels);
        for (size_t i = 0; i < c.theta_i_deg.size() * np * nc; ++i)
            for (const std::string& m : models) {
                const size_t t = i / (np * nc), p = (i / nc) % np;
                std::printf("%-20s %7.2f %7.2f %3zu %-11s", c.name.c_str(), c.theta_i_deg[t],
                            c.phi_i_deg[p], i % nc, m.c_str());
                pm("model_" + m + "_l1_albedo", i, "%.6f");
                pm("model_" + m + "_l2plus_albedo", i, "%.6f");
                pm("l2plus_albedo", i, "%.6f");
                pm("model_" + m + "_albedo", i, "%.6f");
                pm(m + "_l2plus_relative_difference", i, "%+.4f");
                std::printf(" %+7.1f", get(m + "_l2plus_sigmas", i));
                pm(m + "_l2plus_distance", i, "%.4f");
                std::printf("\n");
            }
    }
}

int compare(const std::string& path) {
    const ResultSummary s = read_result_summary(path);
    // One row per incidence, channel and model: the model's albedo against the simulated
    // quantity it models (L1 or every order), their relative difference and how many standard
    // errors it is, the per-cell relative L1 distance; then the simulation's own albedos. Every
    // figure with its standard error.
    std::printf("%-20s %7s %7s %3s %-10s %4s %18s %18s %18s %7s %18s %18s %18s %18s %10s\n", "case",
                "theta_i", "phi_i", "ch", "model", "vs", "model", "sim", "rel_diff", "sigmas",
                "distance", "sim_L1", "sim_L2+", "sim_Linf", "sim_T");
    for (const CaseSummary& c : s.cases) {
        auto get = [&](const std::string& name, size_t i) {
            auto it = c.albedos.find(name);
            return it == c.albedos.end() ? -1.0 : it->second[i];
        };
        // "value±error" (the error is left out when the file has none: an analytic model).
        auto pm = [&](const std::string& name, size_t i, const char* format) {
            char v[64], e[32] = "";
            std::snprintf(v, sizeof v, format, get(name, i));
            if (c.albedos.count(name + "_stderr"))
                std::snprintf(e, sizeof e, "±%.1e", get(name + "_stderr", i));
            std::printf(" %18s", (std::string(v) + e).c_str());
        };
        if (c.albedos.count("l1_albedo") == 0) continue; // a model-only case
        std::vector<std::string> models = c.models;
        if (models.empty()) models.push_back("");
        const size_t np = c.phi_i_deg.size(), nc = c.channels;
        for (size_t t = 0; t < c.theta_i_deg.size(); ++t)
            for (size_t p = 0; p < np; ++p)
                for (size_t k = 0; k < nc; ++k)
                    for (const std::string& m : models) {
                        const size_t i = (t * np + p) * nc + k;
                        std::printf("%-20s %7.2f %7.2f %3zu", c.name.c_str(), c.theta_i_deg[t],
                                    c.phi_i_deg[p], k);
                        if (m.empty()) {
                            std::printf(" %-10s %4s %18s %18s %18s %7s %18s", "-", "-", "-", "-",
                                        "-", "-", "-");
                        } else {
                            const auto vs = c.attributes.find("model_" + m + "_compared_with");
                            const bool all =
                                vs != c.attributes.end() &&
                                enum_named<ModelTarget>(vs->second) == ModelTarget::linf;
                            std::printf(" %-10s %4s", m.c_str(), all ? "Linf" : "L1");
                            pm("model_" + m + "_albedo", i, "%.6f");
                            pm(all ? "linf_albedo" : "l1_albedo", i, "%.6f");
                            pm(m + "_relative_difference", i, "%+.4f");
                            std::printf(" %+7.1f", get(m + "_sigmas", i));
                            pm(m + "_distance", i, "%.4f");
                        }
                        pm("l1_albedo", i, "%.6f");
                        pm("l2plus_albedo", i, "%.6f");
                        pm("linf_albedo", i, "%.6f");
                        if (c.albedos.count("transmitted_albedo")) // dielectrics only
                            std::printf(" %10.6f\n", get("transmitted_albedo", i));
                        else
                            std::printf(" %10s\n", "-");
                    }
    }
    print_orders(s);
    print_decomposition(s);
    // What the errors above include: with one surface, only the rays.
    for (const CaseSummary& c : s.cases)
        if (auto scope = c.attributes.find("error_scope");
            scope != c.attributes.end() &&
            enum_named<ErrorScope>(scope->second) == ErrorScope::rays)
            std::printf("%s: errors are those of the rays on one surface, conditional on it "
                        "(surface.realisations >= 2 includes the surfaces' spread)\n",
                        c.name.c_str());
    return 0;
}

std::function<int()> setup(CLI::App& app, const CliContext&) {
    auto path = std::make_shared<std::string>();
    app.add_option("file", *path, "HDF5 result file")->required();
    return [path] { return compare(*path); };
}
} // namespace

const Command& compare_command() {
    static const Command c{"compare", "Print the Model-vs-simulated table of a result file", setup};
    return c;
}
} // namespace gonio
