#include "gonio/report/report.h"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace gonio {

namespace report_assets {
extern const char* const kPage; // report_page.html, embedded at build time
extern const char* const kApp;  // report.js
} // namespace report_assets

namespace {

// Text safe inside <script>: "</" would end the element early.
std::string script_safe(std::string text) {
    for (size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
        text.replace(at, 2, "<\\/");
    return text;
}

// Replaces the first `marker` at or after `from`; returns where the text put in ends.
size_t substitute(std::string& page, size_t from, const std::string& marker,
                  const std::string& text) {
    const size_t at = page.find(marker, from);
    if (at == std::string::npos) throw std::logic_error("report template without " + marker);
    page.replace(at, marker.size(), text);
    return at + text.size();
}

std::string escape_html(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '&')
            out += "&amp;";
        else
            out += c;
    }
    return out;
}

} // namespace

std::string report_page(const nlohmann::json& data, const std::string& plotly_js) {
    std::string page = report_assets::kPage;
    // Markers are replaced in page order, each searched after the text put in before it.
    size_t at =
        substitute(page, 0, "@TITLE@", escape_html(data.value("file", std::string("result"))));
    at = substitute(page, at, "@PLOTLY@", script_safe(plotly_js));
    at = substitute(
        page, at, "@DATA@",
        script_safe(data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)));
    substitute(page, at, "@APP@", report_assets::kApp);
    return page;
}

std::string read_plotly_js() {
    const char* env = std::getenv("GONIO_PLOTLY_JS");
    const std::string path = env && *env ? env : GONIO_PLOTLY_JS_PATH;
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error(path +
                                 ": cannot read plotly.js (Debian's python3-plotly ships it; "
                                 "$GONIO_PLOTLY_JS names another copy)");
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

} // namespace gonio
