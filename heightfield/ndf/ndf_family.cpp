#include "heightfield/ndf/ndf_family.h"

#include "core/config_error.h"
#include "core/toml_limits.h"

#include <stdexcept>
#include <toml++/toml.h>

namespace gonio {

const std::vector<const NdfFamily*>& ndf_families() {
    static const std::vector<const NdfFamily*> families = {&beckmann_family(),
                                                           &ggx_family(),
                                                           &student_t_family(),
                                                           &generalized_normal_family(),
                                                           &generalized_t_family(),
                                                           &gaussian_family(),
                                                           &piecewise_linear_family(),
                                                           &sinc_family(),
                                                           &blend_family(),
                                                           &mixture_family(),
                                                           &tabulated_family(),
                                                           &height_map_family()};
    return families;
}

const Key& ndf_type_key() {
    static const Key key = [] {
        std::vector<std::string> names;
        for (const NdfFamily* f : ndf_families()) names.push_back(f->name);
        return Key::string("type", names, "microfacet distribution (the keys below)");
    }();
    return key;
}

std::vector<KeyGroup> ndf_key_groups() {
    std::vector<KeyGroup> groups{{"ndf", "", "", {ndf_type_key()}}};
    for (const NdfFamily* f : ndf_families())
        groups.push_back({"ndf", f->name, f->summary, f->keys});
    return groups;
}

std::unique_ptr<Ndf> read_ndf(TableReader r, int depth, const NdfFamily** family) {
    if (depth > 0) { // a nested table has no defaults: its unknown keys are reported here
        std::vector<const std::vector<Key>*> groups;
        static const std::vector<Key> type_only{ndf_type_key()};
        groups.push_back(&type_only);
        for (const NdfFamily* f : ndf_families()) groups.push_back(&f->keys);
        r.allow_only(groups);
    }
    if (depth > 4) r.fail("type", "distributions nest at most 4 deep");
    const std::string type = r.string(ndf_type_key());
    for (const NdfFamily* f : ndf_families()) {
        if (f->name != type) continue;
        if (family) *family = f;
        try {
            return f->create(r, depth);
        } catch (const std::invalid_argument& e) { // a constructor's own check
            r.fail("type", e.what());
        }
    }
    r.fail("type", "no such distribution"); // unreachable: string() checked the choices
}

std::unique_ptr<Ndf> ndf_from_toml(const std::string& table_text) {
    if (const std::string why = toml_limits_problem(table_text); !why.empty())
        throw ConfigError("<ndf>", -1, "", why);
    toml::table t;
    try {
        t = toml::parse(table_text, std::string("<ndf>"));
    } catch (const toml::parse_error& e) {
        throw ConfigError("<ndf>", static_cast<int>(e.source().begin.line), "",
                          "TOML syntax error: " + std::string(e.description()));
    }
    UsageTracker usage;
    return read_ndf(TableReader(&t, "ndf", nullptr, "", "<ndf>", usage), 1);
}

Roughness read_roughness(TableReader& all) {
    const std::vector<Key>& k = roughness_keys();
    const bool own = all.has_own("alpha") || all.has_own("alpha_x") || all.has_own("alpha_y");
    TableReader r = own ? all.own() : all;
    const bool iso = r.has("alpha");
    const bool aniso = r.has("alpha_x") || r.has("alpha_y");
    if (iso && aniso) r.fail("alpha", "give either alpha or both alpha_x and alpha_y, not both");
    if (iso) {
        const double a = r.number(k[0]);
        return {a, a};
    }
    if (!aniso)
        r.fail("alpha", "missing: give alpha (isotropic) or alpha_x and alpha_y; allowed " +
                            k[0].range.describe());
    return {r.number(k[1]), r.number(k[2])};
}

const std::vector<Key>& roughness_keys() {
    static const Range alpha{1e-6, 100};
    static const std::vector<Key> keys = {
        Key::number("alpha", alpha, "isotropic roughness α (Beckmann: slope deviation α/√2)"),
        Key::number("alpha_x", alpha, "anisotropic roughness along x (instead of `alpha`)"),
        Key::number("alpha_y", alpha, "anisotropic roughness along y (instead of `alpha`)")};
    return keys;
}

} // namespace gonio
