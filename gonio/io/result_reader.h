#pragma once
// Reads the summary of a result file: run metadata and, per case and incidence, every stored
// per-incidence quantity (datasets shaped [theta_i, phi_i, channel]: albedos, ledger entries,
// comparison figures), for `gonio info` and `gonio compare`. Reads file formats 1 and 2 (format 1
// stored lists as comma-separated strings and had no timings).
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace gonio {

struct CaseSummary {
    std::string name;
    std::map<std::string, std::string> attributes;       // the group's scalar string attributes
    std::vector<std::string> models, stop;               // stop: per incidence, theta_i major
    std::vector<std::pair<std::string, double>> timings; // phase -> seconds, in order
    std::vector<double> theta_i_deg, phi_i_deg, wavelength_nm;
    int cells = 0;
    int channels = 0;
    // dataset name -> values [theta_i][phi_i][channel]
    std::map<std::string, std::vector<double>> albedos;
    // dataset name -> values [theta_i][phi_i]: rays, rounds, achieved_error, trace_seconds, ...
    std::map<std::string, std::vector<double>> runs;
};

struct ResultSummary {
    std::string path;
    std::map<std::string, std::string> attributes; // root scalar string attributes
    int format = 0;                                // 1 or 2, from file_format
    long long seed = 0;
    std::vector<std::pair<std::string, double>> timings; // phase -> seconds, in order
    std::vector<CaseSummary> cases;
};

// Throws std::runtime_error naming the file if it is missing or not a gonio result file.
ResultSummary read_result_summary(const std::string& path);

} // namespace gonio
