// The fit handed on: Mitsuba 3's and pbrt-v4's material for it, and the TOML / JSON file.
#include "gonio/export/atomic_output.h"
#include "gonio/fit/fit.h"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <toml++/toml.h>

namespace gonio {

namespace {

std::string num(double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
}

double param(const FitResult& r, const std::string& name, double fallback) {
    for (size_t k = 0; k < r.names.size(); ++k)
        if (r.names[k] == name) return r.value[k];
    return fallback;
}

// The case's Schlick F0 per channel: fitted, or the config's Schlick facets'.
std::vector<double> f0_of(const FitResult& r, const FacetSpec& facets) {
    std::vector<double> f0;
    for (size_t k = 0; k < r.names.size(); ++k)
        if (r.names[k].rfind("f0", 0) == 0) f0.push_back(r.value[k]);
    if (f0.empty() && facets.fresnel.kind() == FresnelTerm::Kind::schlick)
        for (int c = 0; c < facets.fresnel.channels(); ++c)
            f0.push_back(facets.fresnel.schlick_f0(c));
    return f0;
}

// Per channel values as "wavelength:value, ..." (Mitsuba) or one value when achromatic.
std::string mitsuba_spectrum(const std::string& name, const std::vector<double>& v,
                             const std::vector<double>& nm) {
    if (v.size() == 1 || nm.size() != v.size())
        return "    <float name=\"" + name + "\" value=\"" + num(v[0]) + "\"/>\n";
    std::string s;
    for (size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + num(nm[k]) + ":" + num(v[k]);
    return "    <spectrum name=\"" + name + "\" value=\"" + s + "\"/>\n";
}
std::string pbrt_spectrum(const std::string& name, const std::vector<double>& v,
                          const std::vector<double>& nm) {
    if (v.size() == 1 || nm.size() != v.size())
        return "\"spectrum " + name + "\" [ 360 " + num(v[0]) + " 830 " + num(v[0]) + " ]";
    std::string s;
    for (size_t k = 0; k < v.size(); ++k) s += " " + num(nm[k]) + " " + num(v[k]);
    return "\"spectrum " + name + "\" [" + s + " ]";
}

std::string ior_name(const FacetSpec& facets) {
    return facets.source.empty() ? "" : std::filesystem::path(facets.source).stem().string();
}

const char* kMultipleScattering =
    "the fit includes multiple scattering (--with); this material is single scattering: add the "
    "renderer's energy compensation";

} // namespace

std::string mitsuba_xml(const FitResult& r, const ResultCase& c) {
    if (r.family != "ggx" && r.family != "beckmann")
        return "<!-- Mitsuba 3's rough BSDFs have the beckmann and ggx distributions only: no "
               "equivalent of " +
               r.family + " -->\n";
    const FacetSpec& facets = c.config.material;
    const std::vector<double>& nm = c.wavelength_nm;
    std::string s;
    if (r.options.with != FitWith::none) s += std::string("<!-- ") + kMultipleScattering + " -->\n";
    const bool glass = facets.transmits;
    s += glass ? "<bsdf type=\"roughdielectric\">\n" : "<bsdf type=\"roughconductor\">\n";
    s += "    <string name=\"distribution\" value=\"" + r.family + "\"/>\n";
    if (r.options.anisotropic)
        s += "    <float name=\"alpha_u\" value=\"" + num(param(r, "alpha_x", 0)) + "\"/>\n" +
             "    <float name=\"alpha_v\" value=\"" + num(param(r, "alpha_y", 0)) + "\"/>\n";
    else
        s += "    <float name=\"alpha\" value=\"" + num(param(r, "alpha", 0)) + "\"/>\n";
    const std::vector<double> f0 = f0_of(r, facets);
    if (glass) {
        s += "    <float name=\"int_ior\" value=\"" + num(facets.fresnel.dielectric_eta(0)) +
             "\"/>\n    <float name=\"ext_ior\" value=\"1\"/>\n";
    } else if (!f0.empty()) {
        s += "    <!-- Schlick's F0 as a constant reflectance: roughconductor has no Schlick term "
             "-->\n"
             "    <string name=\"material\" value=\"none\"/>\n" +
             mitsuba_spectrum("specular_reflectance", f0, nm);
    } else if (facets.fresnel.kind() == FresnelTerm::Kind::mirror) {
        s += "    <string name=\"material\" value=\"none\"/>\n";
    } else if (!ior_name(facets).empty()) {
        s += "    <string name=\"material\" value=\"" + ior_name(facets) + "\"/>\n";
    } else {
        std::vector<double> eta, k;
        for (int ch = 0; ch < facets.fresnel.channels(); ++ch) {
            eta.push_back(facets.fresnel.conductor_eta(ch).real());
            k.push_back(facets.fresnel.conductor_eta(ch).imag());
        }
        s += mitsuba_spectrum("eta", eta, nm) + mitsuba_spectrum("k", k, nm);
    }
    return s + "</bsdf>\n";
}

std::string pbrt_material(const FitResult& r, const ResultCase& c) {
    if (r.family != "ggx")
        return "# pbrt-v4's rough materials use the Trowbridge-Reitz (GGX) distribution only: no "
               "equivalent of " +
               r.family + "\n";
    const FacetSpec& facets = c.config.material;
    const std::vector<double>& nm = c.wavelength_nm;
    std::string rough = r.options.anisotropic
                            ? "\"float uroughness\" " + num(param(r, "alpha_x", 0)) +
                                  " \"float vroughness\" " + num(param(r, "alpha_y", 0))
                            : "\"float roughness\" " + num(param(r, "alpha", 0));
    rough += " \"bool remaproughness\" false";
    std::string s;
    if (r.options.with != FitWith::none) s += std::string("# ") + kMultipleScattering + "\n";
    const std::vector<double> f0 = f0_of(r, facets);
    static const std::set<std::string> named{"Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"};
    if (facets.transmits) {
        s += "Material \"dielectric\" \"float eta\" " + num(facets.fresnel.dielectric_eta(0)) +
             " " + rough;
    } else if (!f0.empty()) {
        s += "Material \"conductor\" " + pbrt_spectrum("reflectance", f0, nm) + " " + rough;
    } else if (facets.fresnel.kind() == FresnelTerm::Kind::mirror) {
        s += "Material \"conductor\" \"spectrum reflectance\" [ 360 1 830 1 ] " + rough;
    } else if (named.count(ior_name(facets))) {
        const std::string m = "metal-" + ior_name(facets);
        s += "Material \"conductor\" \"spectrum eta\" \"" + m + "-eta\" \"spectrum k\" \"" + m +
             "-k\" " + rough;
    } else {
        std::vector<double> eta, k;
        for (int ch = 0; ch < facets.fresnel.channels(); ++ch) {
            eta.push_back(facets.fresnel.conductor_eta(ch).real());
            k.push_back(facets.fresnel.conductor_eta(ch).imag());
        }
        s += "Material \"conductor\" " + pbrt_spectrum("eta", eta, nm) + " " +
             pbrt_spectrum("k", k, nm) + " " + rough;
    }
    return s + "\n";
}

void write_fit(const FitResult& r, const std::string& path) {
    const ResultCase c = read_result_case(r.file, r.case_name);
    const bool json = std::filesystem::path(path).extension() == ".json";
    auto nan_free = [](double v) {
        return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
    };
    AtomicOutput out(path, true, false);
    if (json) {
        nlohmann::json j;
        j["fit"] = {{"file", r.file},
                    {"case", r.case_name},
                    {"data", r.data},
                    {"model", r.family},
                    {"anisotropic", r.options.anisotropic},
                    {"loss", name_of(r.options.loss)},
                    {"orders", name_of(r.options.orders)},
                    {"with", name_of(r.options.with)},
                    {"fresnel", name_of(r.options.fresnel)},
                    {"max_theta", r.options.max_theta_deg},
                    {"points", r.points},
                    {"chi2", r.chi2},
                    {"chi2_per_dof", r.chi2_per_dof()},
                    {"loss_value", r.loss},
                    {"starts", r.starts},
                    {"converged", r.converged},
                    {"seconds", r.seconds}};
        for (size_t k = 0; k < r.names.size(); ++k) {
            nlohmann::json p = {{"value", r.value[k]},
                                {"stderr", nan_free(r.stderr_covariance[k])},
                                {"lower", r.lower[k]},
                                {"upper", r.upper[k]}};
            if (!r.stderr_bootstrap.empty()) p["stderr_bootstrap"] = r.stderr_bootstrap[k];
            j["parameters"][r.names[k]] = p;
        }
        j["ndf"] = r.ndf_toml;
        j["mitsuba3"] = mitsuba_xml(r, c);
        j["pbrt_v4"] = pbrt_material(r, c);
        nlohmann::json map = nlohmann::json::array();
        for (double v : r.residual_map) map.push_back(nan_free(v));
        j["residuals"] = {{"theta_i", r.theta_i_deg},
                          {"phi_i", r.phi_i_deg},
                          {"cells", r.cells},
                          {"channels", r.channels},
                          {"normalised", map}};
        out.stream() << j.dump(1) << "\n";
    } else {
        toml::table fit{{"file", r.file},
                        {"case", r.case_name},
                        {"data", r.data},
                        {"model", r.family},
                        {"anisotropic", r.options.anisotropic},
                        {"loss", std::string(name_of(r.options.loss))},
                        {"orders", std::string(name_of(r.options.orders))},
                        {"with", std::string(name_of(r.options.with))},
                        {"fresnel", std::string(name_of(r.options.fresnel))},
                        {"max_theta", r.options.max_theta_deg},
                        {"points", r.points},
                        {"chi2", r.chi2},
                        {"chi2_per_dof", r.chi2_per_dof()},
                        {"loss_value", r.loss},
                        {"starts", r.starts},
                        {"converged", r.converged},
                        {"seconds", r.seconds},
                        {"residuals", "in the JSON form of the fit (-o FIT.json)"}};
        toml::table params;
        for (size_t k = 0; k < r.names.size(); ++k) {
            toml::table p{{"value", r.value[k]}, {"lower", r.lower[k]}, {"upper", r.upper[k]}};
            if (std::isfinite(r.stderr_covariance[k])) p.insert("stderr", r.stderr_covariance[k]);
            if (!r.stderr_bootstrap.empty()) p.insert("stderr_bootstrap", r.stderr_bootstrap[k]);
            params.insert(r.names[k], p);
        }
        toml::table root{{"fit", fit},
                         {"parameters", params},
                         {"ndf", toml::parse(r.ndf_toml)},
                         {"renderers", toml::table{{"mitsuba3", mitsuba_xml(r, c)},
                                                   {"pbrt_v4", pbrt_material(r, c)}}}};
        out.stream() << "# gonio fit: " << r.family << " fitted to " << r.data << " of case "
                     << r.case_name << " in " << r.file << "\n"
                     << root << "\n";
    }
    out.commit();
}

} // namespace gonio
