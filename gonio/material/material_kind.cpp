#include "gonio/material/material_kind.h"

#include "gonio/material/ior_table.h"

namespace gonio {

namespace {
const Key kWavelengths = Key::numbers("wavelengths", {200, 20000},
                                      "one channel each, for spectral materials (at most 64)")
                             .in_unit("nm")
                             .fallback(std::vector<double>{650, 550, 450});

const Key& type_key() {
    static const Key key = [] {
        std::vector<std::string> names;
        for (const MaterialKind* k : material_kinds()) names.push_back(k->name);
        return Key::string("type", names, "what a facet does (the keys below)").fallback("mirror");
    }();
    return key;
}

std::vector<std::unique_ptr<Material>> one_part(std::unique_ptr<Material> m) {
    std::vector<std::unique_ptr<Material>> parts;
    parts.push_back(std::move(m));
    return parts;
}

// A specular facet: every kind but the diffuse ones reflects with its Fresnel term.
FacetSpec specular(std::string type, FresnelTerm fresnel) {
    FacetSpec s;
    s.type = std::move(type);
    s.description = fresnel.describe();
    s.channels = fresnel.channels();
    s.fresnel = fresnel;
    s.parts = [fresnel] { return one_part(std::make_unique<SpecularReflector>(fresnel)); };
    return s;
}

const Key kIor = Key::string("ior", {},
                             "conductor: a table in data/ior/ (\"Au\", \"Ag\", \"Cu\", "
                             "\"Al\") or a CSV path")
                     .note_default("—");
const Key kN = Key::numbers("n", {1e-3, 100},
                            "conductor: real part of the index (with k, "
                            "instead of ior; one or per wavelength)")
                   .note_default("—");
const Key kK = Key::numbers("k", {0, 100}, "conductor: imaginary part (one or per wavelength)")
                   .note_default("—");
const Key kEta = Key::numbers("eta", {1e-3, 100},
                              "dielectric: index ratio below/above the surface (1: no interface)")
                     .cited("M18 Eq. 8");
const Key kF0 =
    Key::numbers("f0", {0, 1}, "Schlick: normal-incidence reflectance (one or per wavelength)");
const Key kAlbedo = Key::numbers("albedo", {0, 1},
                                 "Lambertian facets: albedo (one or per "
                                 "wavelength)");
} // namespace

std::string list_text(const std::vector<double>& v) {
    std::string s;
    for (double x : v) s += (s.empty() ? "" : ", ") + shortest(x);
    return s;
}

std::vector<double> read_wavelengths(TableReader& spectrum) {
    std::vector<double> w = spectrum.number_list(kWavelengths);
    if (w.size() > size_t(kMaxChannels))
        spectrum.fail("wavelengths", "has " + std::to_string(w.size()) + " values; at most " +
                                         std::to_string(kMaxChannels) + " channels");
    return w;
}

std::vector<double> read_per_channel(TableReader& r, const Key& key, TableReader& spectrum,
                                     std::vector<double>& wavelengths) {
    std::vector<double> v = r.number_list(key);
    if (v.size() > 1) { // spectral: one value per wavelength
        if (wavelengths.empty()) wavelengths = read_wavelengths(spectrum);
        if (v.size() != wavelengths.size())
            r.fail(key.name, "has " + std::to_string(v.size()) +
                                 " values; give one (achromatic) or one per wavelength (" +
                                 std::to_string(wavelengths.size()) + ")");
    }
    return v;
}

const MaterialKind& mirror_kind() {
    static const MaterialKind k{
        "mirror", "a perfect mirror (F = 1)", {}, [](TableReader&, TableReader&) {
            return specular("mirror", FresnelTerm::mirror());
        }};
    return k;
}

const MaterialKind& conductor_kind() {
    static const MaterialKind k{
        "conductor",
        "a conductor's exact Fresnel reflectance (complex index)",
        {kIor, kN, kK},
        [](TableReader& r, TableReader& spectrum) {
            std::vector<double> wavelengths = read_wavelengths(spectrum);
            std::vector<std::complex<double>> eta;
            std::string source;
            if (r.has("ior")) {
                if (r.has("n") || r.has("k"))
                    r.fail("ior", "give either ior (a table) or n and k, not both");
                const std::string file = resolve_ior_path(r.string(kIor));
                IorTable table = [&]() {
                    try {
                        return IorTable::load(file);
                    } catch (const std::exception& e) {
                        r.fail("ior", std::string(e.what()) +
                                          " (a name such as \"Au\", \"Ag\", \"Cu\", \"Al\" or a "
                                          "path to a CSV)");
                    }
                }();
                for (double w : wavelengths) {
                    if (w < table.min_wavelength() || w > table.max_wavelength())
                        spectrum.fail("wavelengths",
                                      "wavelength " + shortest(w) + " nm is outside table " + file +
                                          "; allowed [" + shortest(table.min_wavelength()) + ", " +
                                          shortest(table.max_wavelength()) + "] nm");
                    eta.push_back(table.at(w));
                }
                source = file;
            } else {
                const std::vector<double> n = read_per_channel(r, kN, spectrum, wavelengths);
                const std::vector<double> k = read_per_channel(r, kK, spectrum, wavelengths);
                for (size_t i = 0; i < wavelengths.size(); ++i)
                    eta.emplace_back(n[n.size() == 1 ? 0 : i], k[k.size() == 1 ? 0 : i]);
            }
            FacetSpec s = specular("conductor", FresnelTerm::conductor(eta));
            s.wavelengths_nm = wavelengths;
            s.source = source;
            return s;
        }};
    return k;
}

const MaterialKind& schlick_kind() {
    static const MaterialKind k{
        "schlick",
        "Schlick's approximation of the reflectance",
        {kF0},
        [](TableReader& r, TableReader& spectrum) {
            std::vector<double> wavelengths;
            FacetSpec s = specular(
                "schlick", FresnelTerm::schlick(read_per_channel(r, kF0, spectrum, wavelengths)));
            s.wavelengths_nm = wavelengths;
            return s;
        }};
    return k;
}

const MaterialKind& dielectric_kind() {
    static const MaterialKind k{
        "dielectric",
        "a smooth dielectric interface, reflection and refraction [M18 Eq. 8]",
        {kEta},
        [](TableReader& r, TableReader& spectrum) {
            std::vector<double> wavelengths;
            const FresnelTerm fresnel =
                FresnelTerm::dielectric(read_per_channel(r, kEta, spectrum, wavelengths));
            FacetSpec s = specular("dielectric", fresnel);
            s.wavelengths_nm = wavelengths;
            s.transmits = true;
            // Each channel refracts its own way: traced one by one.
            s.parts = [fresnel] {
                std::vector<std::unique_ptr<Material>> parts;
                for (int c = 0; c < fresnel.channels(); ++c)
                    parts.push_back(std::make_unique<DielectricFacet>(fresnel.dielectric_eta(c)));
                return parts;
            };
            return s;
        }};
    return k;
}

const MaterialKind& lambertian_kind() {
    static const MaterialKind k{
        "lambertian", "Lambertian facets", {kAlbedo}, [](TableReader& r, TableReader& spectrum) {
            FacetSpec s;
            s.type = "lambertian";
            s.diffuse = true;
            s.albedo = read_per_channel(r, kAlbedo, spectrum, s.wavelengths_nm);
            s.interface_eta = {1.0};
            s.channels = int(s.albedo.size());
            s.description = "lambertian(albedo=" + list_text(s.albedo) + ")";
            const std::vector<double> albedo = s.albedo;
            s.parts = [albedo] { return one_part(std::make_unique<LambertianFacet>(albedo)); };
            return s;
        }};
    return k;
}

const std::vector<const MaterialKind*>& material_kinds() {
    static const std::vector<const MaterialKind*> kinds = {
        &mirror_kind(),  &conductor_kind(),  &dielectric_kind(),
        &schlick_kind(), &lambertian_kind(), &interfaced_lambertian_kind()};
    return kinds;
}

FacetSpec read_material(TableReader r, TableReader spectrum) {
    const std::string type = r.string(type_key());
    for (const MaterialKind* k : material_kinds())
        if (k->name == type) return k->create(r, spectrum);
    r.fail("type", "no such material"); // unreachable: string() checked the choices
}

std::vector<KeyGroup> material_key_groups() {
    std::vector<KeyGroup> groups{{"material", "", "", {type_key()}}};
    for (const MaterialKind* k : material_kinds())
        if (!k->keys.empty()) groups.push_back({"material", k->name, k->summary, k->keys});
    groups.push_back({"spectrum", "", "", {kWavelengths}});
    return groups;
}

} // namespace gonio
