// The tabulated BSDF's interpolation error, measured against directly traced incidences:
//   table_interpolation SWEEP.h5 HELD_OUT.h5 [--order linf|l1|l2plus]
// builds the table from the sweep's case and, for every incidence of the held-out file's case
// (the same surface, traced at angles the sweep does not hold), compares the table at the cell
// centres with the traced cell averages over the bright cells (>= 10 % of the peak), and the
// table's albedo with the traced albedo. Prints one JSON object per held-out incidence (for
// bench/table_study.py, which tabulates them).
#include "gonio/table/bsdf_table.h"
#include "gonio/table/result_case.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace gonio;

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: table_interpolation SWEEP.h5 HELD_OUT.h5 [--order O]\n");
        return 2;
    }
    const std::string order_name =
        argc >= 5 && std::string(argv[3]) == "--order" ? argv[4] : "linf";
    try {
        const TableOrder order = enum_named<TableOrder>(order_name);
        const ResultCase sweep = read_result_case(argv[1], "");
        const ResultCase held = read_result_case(argv[2], "");
        const BsdfTable table(table_data(sweep, order));
        const TableData h = table_data(held, order);
        if (h.cells != table.data().cells) throw std::runtime_error("different sensors");
        const BeckersSensor sensor(h.cells);
        const std::string albedo_name = order_name + "_albedo";
        const auto albedo = held.read_albedo(albedo_name),
                   albedo_err = held.read_albedo(albedo_name + "_stderr");
        const size_t C = size_t(h.channels), N = size_t(h.cells);
        std::vector<double> f(C);
        for (size_t ti = 0; ti < h.theta_i_deg.size(); ++ti)
            for (size_t pj = 0; pj < h.phi_i_deg.size(); ++pj) {
                const size_t inc = ti * h.phi_i_deg.size() + pj;
                const Vec3 wi =
                    spherical_direction(radians(h.theta_i_deg[ti]), radians(h.phi_i_deg[pj]));
                std::vector<double> rel, noise;
                double worst_albedo = 0, albedo_sigma = 0;
                std::vector<double> a(C);
                table.albedo(wi, a.data());
                for (size_t ch = 0; ch < C; ++ch) {
                    const double* v = h.f.data() + inc * N * C;
                    double peak = 0;
                    for (size_t c = 0; c < N; ++c) peak = std::max(peak, v[c * C + ch]);
                    for (size_t c = 0; c < N; ++c) {
                        const double traced = v[c * C + ch];
                        if (traced < 0.1 * peak) continue;
                        table.eval(wi, sensor.cell(int(c)).center, f.data());
                        rel.push_back(std::abs(f[ch] / traced - 1));
                        noise.push_back(h.f_stderr[(inc * N + c) * C + ch] / traced);
                    }
                    const double e = a[ch] / albedo[inc * C + ch] - 1;
                    if (std::abs(e) >= std::abs(worst_albedo)) {
                        worst_albedo = e;
                        albedo_sigma = albedo_err[inc * C + ch] / albedo[inc * C + ch];
                    }
                }
                std::sort(rel.begin(), rel.end());
                std::sort(noise.begin(), noise.end());
                auto q = [](const std::vector<double>& v, double p) {
                    return v.empty() ? 0.0 : v[std::min(v.size() - 1, size_t(p * v.size()))];
                };
                std::printf("{\"theta_i\": %.6g, \"phi_i\": %.6g, \"cells\": %zu, "
                            "\"median_cell_error\": %.6g, \"p90_cell_error\": %.6g, "
                            "\"median_cell_noise\": %.6g, \"albedo_error\": %.6g, "
                            "\"albedo_noise\": %.6g}\n",
                            h.theta_i_deg[ti], h.phi_i_deg[pj], rel.size(), q(rel, 0.5),
                            q(rel, 0.9), q(noise, 0.5), worst_albedo, albedo_sigma);
            }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "table_interpolation: %s\n", e.what());
        return 1;
    }
    return 0;
}
