#include "core/math.h"
#include "gonio/io/result_reader.h"
#include "gonio/report/report.h"
#include "gonio/table/result_case.h"
#include "heightfield/ndf/ndf_family.h"
#include "sensor/beckers_sensor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>

namespace gonio {

namespace {

using json = nlohmann::ordered_json;

// Pixels per side of the hemisphere maps (Lambert equal-area disk: cells keep their equal areas).
constexpr int kMapPixels = 129;

std::string base64(const unsigned char* bytes, size_t n) {
    static const char* alphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((n + 2) / 3 * 4);
    for (size_t i = 0; i < n; i += 3) {
        const unsigned v = unsigned(bytes[i]) << 16 |
                           (i + 1 < n ? unsigned(bytes[i + 1]) << 8 : 0) |
                           (i + 2 < n ? unsigned(bytes[i + 2]) : 0);
        out += alphabet[v >> 18 & 63];
        out += alphabet[v >> 12 & 63];
        out += i + 1 < n ? alphabet[v >> 6 & 63] : '=';
        out += i + 2 < n ? alphabet[v & 63] : '=';
    }
    return out;
}

// Little-endian float32 in base64: the maps are most of a page's bytes, and the page decodes them
// with atob into a Float32Array (x86-64 and every browser platform are little-endian).
std::string base64_floats(const std::vector<double>& values) {
    std::vector<unsigned char> bytes(values.size() * 4);
    for (size_t i = 0; i < values.size(); ++i) {
        const float f = static_cast<float>(values[i]);
        std::memcpy(&bytes[4 * i], &f, 4);
    }
    return base64(bytes.data(), bytes.size());
}

// The cell under each pixel of the equal-area disk (-1 outside): r = sin(theta/2) / sin(45 deg).
std::vector<int> pixel_cells(const BeckersSensor& sensor) {
    std::vector<int> cells(size_t(kMapPixels) * kMapPixels, -1);
    for (int row = 0; row < kMapPixels; ++row)
        for (int col = 0; col < kMapPixels; ++col) {
            const double x = 2.0 * (col + 0.5) / kMapPixels - 1.0;
            const double y = 2.0 * (row + 0.5) / kMapPixels - 1.0;
            const double r = std::sqrt(x * x + y * y);
            if (r > 1.0) continue;
            const double theta = 2.0 * std::asin(r * std::sin(0.25 * kPi));
            double phi = std::atan2(y, x);
            if (phi < 0) phi += kTwoPi;
            cells[size_t(row) * kMapPixels + col] = sensor.lookup(spherical_direction(theta, phi));
        }
    return cells;
}

json sensor_json(const BeckersSensor& sensor) {
    json s;
    std::vector<double> t0, t1, p0, p1;
    for (int c = 0; c < sensor.cell_count(); ++c) {
        const SensorCell& cell = sensor.cell(c);
        t0.push_back(degrees(cell.theta_min));
        t1.push_back(degrees(cell.theta_max));
        p0.push_back(degrees(cell.phi_min));
        p1.push_back(degrees(cell.phi_max));
    }
    s["cells"] = sensor.cell_count();
    s["theta_min"] = t0;
    s["theta_max"] = t1;
    s["phi_min"] = p0;
    s["phi_max"] = p1;
    s["pixels"] = kMapPixels;
    s["pixel_cell"] = pixel_cells(sensor);
    return s;
}

// D(theta) along phi = 0 and 90 degrees, at 0.5-degree steps to 89.5.
json ndf_curves(const Ndf& ndf) {
    json out;
    std::vector<double> theta, d0, d90;
    for (int k = 0; k < 180; ++k) {
        const double t = 0.5 * k;
        theta.push_back(t);
        d0.push_back(ndf.D(spherical_direction(radians(t), 0.0)));
        d90.push_back(ndf.D(spherical_direction(radians(t), 0.5 * kPi)));
    }
    out["theta"] = theta;
    out["phi0"] = d0;
    out["phi90"] = d90;
    return out;
}

// The first surface's height map named in the case's `surface` attribute, when it is still there.
std::string surface_file(const std::string& description) {
    const size_t end = description.rfind(".exr");
    if (end == std::string::npos) return "";
    const size_t start = description.rfind(' ', end);
    const std::string path =
        description.substr(start == std::string::npos ? 0 : start + 1, end + 4 - (start + 1));
    return std::filesystem::exists(path) ? path : "";
}

std::string attribute(const std::map<std::string, std::string>& a, const std::string& key) {
    const auto it = a.find(key);
    return it == a.end() ? "" : it->second;
}

json case_json(const ResultSummary& summary, const CaseSummary& s) {
    const ResultCase c = read_result_case(summary.path, s.name);
    json out;
    out["name"] = s.name;
    json attrs = json::object();
    for (const auto& [k, v] : s.attributes) attrs[k] = v;
    out["attributes"] = attrs;
    out["theta_i"] = c.theta_i_deg;
    out["phi_i"] = c.phi_i_deg;
    out["wavelength"] = c.wavelength_nm;
    out["channels"] = c.channels;
    out["simulated"] = c.simulated;
    out["transmits"] = c.transmits;
    out["models"] = s.models;
    json compared = json::object();
    for (const std::string& m : s.models)
        compared[m] = attribute(s.attributes, "model_" + m + "_compared_with");
    out["compared_with"] = compared;
    json timings = json::object();
    for (const auto& [phase, seconds] : s.timings) timings[phase] = seconds;
    out["timings"] = timings;
    json runs = json::object();
    for (const auto& [k, v] : s.runs) runs[k] = v;
    out["runs"] = runs;
    out["stop"] = s.stop;

    // Maps [theta_i][phi_i][cell][channel]; L-infinity is L1 + L2+, computed by the page.
    json maps = json::object();
    auto put_map = [&](const std::string& key, const std::string& dataset) {
        if (c.has(dataset)) maps[key] = base64_floats(c.read_map(dataset));
    };
    if (c.simulated) {
        put_map("l1", "brdf_l1");
        put_map("l1_stderr", "brdf_l1_stderr");
        put_map("l2plus", "brdf_l2plus");
        put_map("l2plus_stderr", "brdf_l2plus_stderr");
        bool every_order = false;
        for (const std::string& m : s.models)
            every_order |= attribute(s.attributes, "model_" + m + "_compared_with") == "linf";
        if (every_order) put_map("linf_stderr", "brdf_linf_stderr");
        if (c.transmits) put_map("t", "btdf_tinf");
    }
    for (const std::string& m : s.models) {
        put_map("model_" + m, "model_" + m);
        put_map("model_" + m + "_stderr", "model_" + m + "_stderr");
        put_map("model_" + m + "_l2plus", "model_" + m + "_l2plus");
        put_map("model_" + m + "_l2plus_stderr", "model_" + m + "_l2plus_stderr");
    }
    out["maps"] = maps;

    // Per incidence [theta_i][phi_i][channel]: albedos, their errors and the ledger.
    json albedos = json::object();
    for (const auto& [k, v] : s.albedos) albedos[k] = v;
    out["albedos"] = albedos;

    json ndf;
    ndf["target"] = ndf_curves(*c.config.ndf);
    ndf["target_description"] = c.config.ndf->describe();
    const std::string surface = surface_file(attribute(s.attributes, "surface"));
    if (!surface.empty()) {
        try {
            const auto measured =
                ndf_from_toml("type = \"height_map\"\nfile = " + json(surface).dump() + "\n");
            ndf["measured"] = ndf_curves(*measured);
            ndf["measured_file"] = surface;
        } catch (const std::exception& e) {
            ndf["measured_note"] = std::string("the surface could not be read: ") + e.what();
        }
    } else if (const std::string text = attribute(s.attributes, "surface");
               text.find(" (read: ") != std::string::npos) {
        ndf["measured_note"] = "a measured map: " + text; // docs/measured-surfaces.md
    } else {
        ndf["measured_note"] =
            c.simulated ? "the surface is no longer in the cache" : "no surface (gonio model)";
    }
    out["ndf"] = ndf;
    return out;
}

std::string png_data_url(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot read the image");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() < 8 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0)
        throw std::runtime_error(path + ": not a PNG image (--image takes gonio render's PNG)");
    return "data:image/png;base64," +
           base64(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
}

} // namespace

nlohmann::json report_data(const ReportSource& source) {
    const ResultSummary summary = read_result_summary(source.result);
    json data;
    data["file"] = std::filesystem::path(source.result).filename().string();
    json attrs = json::object();
    for (const auto& [k, v] : summary.attributes) attrs[k] = v;
    data["attributes"] = attrs;
    data["seed"] = summary.seed;
    json timings = json::object();
    for (const auto& [phase, seconds] : summary.timings) timings[phase] = seconds;
    data["timings"] = timings;
    json sensors = json::object(); // one per cell count
    json cases = json::array();
    for (const CaseSummary& s : summary.cases) {
        const std::string key = std::to_string(s.cells);
        if (!sensors.contains(key)) sensors[key] = sensor_json(BeckersSensor(s.cells));
        cases.push_back(case_json(summary, s));
        cases.back()["sensor"] = key;
    }
    data["sensors"] = sensors;
    data["cases"] = cases;
    json images = json::array();
    for (const std::string& path : source.images)
        images.push_back({{"name", std::filesystem::path(path).filename().string()},
                          {"src", png_data_url(path)}});
    data["images"] = images;
    // Fits of the file's cases (gonio fit -o FIT.json): parameters, and the residual map (data -
    // fit) / sigma, shown beside the case's maps.
    json fits = json::array();
    for (const std::string& path : source.fits) {
        std::ifstream in(path);
        if (!in) throw std::runtime_error(path + ": cannot read the fit");
        json f;
        try {
            in >> f;
        } catch (const std::exception& e) {
            throw std::runtime_error(path + ": not a gonio fit JSON file (" + e.what() + ")");
        }
        if (!f.contains("fit") || !f.contains("parameters") || !f.contains("residuals"))
            throw std::runtime_error(path + ": not a gonio fit JSON file (gonio fit -o FIT.json)");
        const std::string name = f["fit"].value("case", "");
        const auto it = std::find_if(summary.cases.begin(), summary.cases.end(),
                                     [&](const CaseSummary& c) { return c.name == name; });
        if (it == summary.cases.end())
            throw std::runtime_error(path + ": a fit of case '" + name + "', which " +
                                     source.result + " does not hold");
        const json& r = f["residuals"];
        const size_t expected = it->theta_i_deg.size() * it->phi_i_deg.size() * size_t(it->cells) *
                                size_t(it->channels);
        if (!r["normalised"].is_array() || r["normalised"].size() != expected)
            throw std::runtime_error(path + ": its residual map does not fit case " + name);
        std::vector<double> z;
        for (const json& v : r["normalised"])
            z.push_back(v.is_number() ? v.get<double>() : std::nan(""));
        fits.push_back({{"file", std::filesystem::path(path).filename().string()},
                        {"case", name},
                        {"fit", f["fit"]},
                        {"parameters", f["parameters"]},
                        {"residuals", base64_floats(z)}});
    }
    data["fits"] = fits;
    return nlohmann::json(data);
}

} // namespace gonio
