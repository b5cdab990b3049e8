#pragma once
// `gonio report`: one self-contained HTML page per result file. The data a page shows is gathered
// here from the file (summary, per-cell maps, albedos, ledger, the surface's facet NDF against its
// target); the page itself is the page template (report_page.html, report.js) with plotly.js from
// Debian's python3-plotly and the data embedded, so it opens without a network.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace gonio {

struct ReportSource {
    std::string result;              // the HDF5 result file
    std::vector<std::string> images; // PNG renders to show with it (gonio render's output)
    std::vector<std::string> fits;   // gonio fit's JSON files of its cases (parameters, residuals)
};

// The page's data. Throws std::runtime_error naming the file and dataset when the file cannot be
// read (the readers' checks: shapes against axes, finite values).
nlohmann::json report_data(const ReportSource& source);

// The format a file says it has ("gonio-result 2", "gonio-masking 1"; "" when it says none).
// Throws std::runtime_error when it is missing, damaged (its checksum) or no HDF5 file.
std::string file_format_of(const std::string& path);
// The data of a gonio masking file's page (G1, the furnace, G2 against Smith's forms).
nlohmann::json masking_report_data(const std::string& path);

// The whole page: `plotly_js` is the library's source, embedded as it is.
std::string report_page(const nlohmann::json& data, const std::string& plotly_js);

// plotly.js: $GONIO_PLOTLY_JS, else the file Debian's python3-plotly ships. Throws
// std::runtime_error saying where it looked.
std::string read_plotly_js();

} // namespace gonio
