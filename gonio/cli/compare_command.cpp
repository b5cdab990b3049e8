#include "gonio/cli/commands.h"
#include "gonio/io/result_reader.h"

#include <cstdio>

namespace gonio {

int run_compare_command(const std::string& path) {
    const ResultSummary s = read_result_summary(path);
    std::printf("%-20s %7s %7s %3s %10s %10s %10s %10s %10s %10s %10s\n", "case", "theta_i",
                "phi_i", "ch", "model_L1", "sim_L1", "rel_diff", "L1_dist", "sim_L2+", "sim_Linf",
                "sim_T");
    for (const CaseSummary& c : s.cases) {
        auto get = [&](const char* name, size_t i) {
            auto it = c.albedos.find(name);
            return it == c.albedos.end() ? -1.0 : it->second[i];
        };
        if (c.albedos.count("l1_albedo") == 0) continue; // a model-only case
        const size_t np = c.phi_i_deg.size(), nc = c.channels;
        for (size_t t = 0; t < c.theta_i_deg.size(); ++t)
            for (size_t p = 0; p < np; ++p)
                for (size_t k = 0; k < nc; ++k) {
                    const size_t i = (t * np + p) * nc + k;
                    std::printf("%-20s %7.2f %7.2f %3zu", c.name.c_str(), c.theta_i_deg[t],
                                c.phi_i_deg[p], k);
                    if (c.albedos.count("model_l1_albedo"))
                        std::printf(" %10.6f %10.6f %+10.4f %10.4f", get("model_l1_albedo", i),
                                    get("l1_albedo", i), get("l1_relative_difference", i),
                                    get("l1_distance", i));
                    else
                        std::printf(" %10s %10.6f %10s %10s", "-", get("l1_albedo", i), "-", "-");
                    std::printf(" %10.6f %10.6f", get("l2plus_albedo", i), get("linf_albedo", i));
                    if (c.albedos.count("transmitted_albedo")) // dielectrics only
                        std::printf(" %10.6f\n", get("transmitted_albedo", i));
                    else
                        std::printf(" %10s\n", "-");
                }
    }
    return 0;
}

} // namespace gonio
