#include "gonio/config/config.h"

#include "core/config_error.h"
#include "core/float_mode.h"
#include "core/message.h"
#include "core/table_reader.h"
#include "core/toml_limits.h"
#include "gonio/config/overrides.h"
#include "heightfield/ndf/ndf_family.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <toml++/toml.h>

namespace gonio {

namespace {

const Key kSeed = Key::integer("seed", {0, 9.2e18},
                               "seed of every random stream, stored in the "
                               "result")
                      .fallback(1.0);
const Key kName =
    Key::string("name", {}, "case name (HDF5 group), of `A-Za-z0-9_.-+`").note_default("file stem");
const Key kCase =
    Key::tables("case", "the cases: each overrides any section above").note_default("one case");
// Below 90 by a margin: a beam's ray crosses about relief tan(theta_i) / L side walls before it
// reaches the surface (at 89.99 deg, 5730 relief / L), so that every accepted incidence ends.
const Key kThetaI =
    Key::numbers("theta_i", {0, 89.99}, "incidence polar angle; a sweep, in increasing order")
        .in_unit("degrees")
        .note_default("— (`gonio run`, `gonio model`)");
const Key kPhiI = Key::numbers("phi_i", {0, 360}, "incidence azimuth; a sweep, in increasing order")
                      .in_unit("degrees")
                      .fallback(std::vector<double>{0.0});
const Key kCells =
    Key::integer("cells", {1, 1e7}, "Beckers equal-area cells on the hemisphere").fallback(3240.0);

// The sections a case may hold, in the order of docs/configuration.md.
const std::vector<std::string> kSections = {"ndf",    "material", "spectrum", "beam",
                                            "sensor", "model",    "surface",  "trace"};

std::string join(const std::string& a, const std::string& b) {
    return a.empty() ? b : a + "." + b;
}

// Every key name a section may hold (the union over its components); anything else is unknown.
const std::map<std::string, std::vector<std::string>>& schema() {
    static const std::map<std::string, std::vector<std::string>> s = [] {
        std::map<std::string, std::vector<std::string>> m;
        auto add = [&](const std::string& section, const std::string& key) {
            auto& v = m[section];
            if (std::find(v.begin(), v.end(), key) == v.end()) v.push_back(key);
        };
        for (const KeyGroup& g : config_key_groups())
            for (const Key& k : g.keys) add(g.section, k.name);
        for (const std::string& sec : kSections) add("", sec), add("case", sec);
        add("case", "name");
        return m;
    }();
    return s;
}

// The keys of a section that a component of type `type` reads (none when no component is named
// `type`): the section's common keys and the component's own.
std::vector<std::string> keys_of(const std::string& section, const std::string& type) {
    std::vector<std::string> out;
    bool found = false;
    for (const KeyGroup& g : config_key_groups()) {
        if (g.section != section || (!g.owner.empty() && g.owner != type)) continue;
        found = found || g.owner == type;
        for (const Key& k : g.keys)
            if (std::find(out.begin(), out.end(), k.name) == out.end()) out.push_back(k.name);
    }
    return found && !type.empty() ? out : std::vector<std::string>{};
}

class Loader {
  public:
    Loader(const toml::table& root, std::string file) : root_(root), file_(std::move(file)) {}

    Config load() {
        Config cfg;
        check_sections(root_, "", "");
        TableReader top(&root_, "", nullptr, "", file_, usage_);
        cfg.seed = static_cast<std::uint64_t>(top.integer(kSeed));
        seed_ = cfg.seed;
        const toml::node* cases = root_.get("case");
        if (cases) {
            usage_.mark(cases);
            const toml::array* arr = cases->as_array();
            if (!arr || !arr->is_array_of_tables() || arr->empty())
                throw ConfigError(file_, line(cases), "case",
                                  "must be an array of tables: [[case]] sections");
            for (size_t k = 0; k < arr->size(); ++k) {
                const toml::table& t = *(*arr)[k].as_table();
                const std::string path = "case[" + std::to_string(k) + "]";
                check_sections(t, "case", path);
                cfg.cases.push_back(load_case(&t, path));
            }
        } else {
            cfg.cases.push_back(load_case(nullptr, ""));
        }
        check_names(cfg);
        report_unused(root_, "");
        return cfg;
    }

  private:
    static int line(const toml::node* n) {
        return n ? static_cast<int>(n->source().begin.line) : 0;
    }

    // Unknown keys are reported at once, with a suggestion.
    void check_sections(const toml::table& t, const std::string& kind, const std::string& path) {
        const auto& allowed = schema().at(kind);
        for (const auto& [k, v] : t) {
            const std::string key(k.str());
            if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
                unknown(key, v, allowed, path);
            if (std::find(kSections.begin(), kSections.end(), key) != kSections.end()) {
                const toml::table* sec = v.as_table();
                if (!sec) throw ConfigError(file_, line(&v), join(path, key), "must be a table");
                usage_.mark(&v);
                const auto& sec_allowed = schema().at(key);
                for (const auto& [sk, sv] : *sec) {
                    const std::string skey(sk.str());
                    if (std::find(sec_allowed.begin(), sec_allowed.end(), skey) !=
                        sec_allowed.end())
                        continue;
                    // Name the keys of the section's own type when it gives one.
                    const std::vector<std::string> own =
                        keys_of(key, sec->get("type") ? sec->get("type")->value_or(std::string())
                                                      : std::string());
                    unknown(skey, sv, own.empty() ? sec_allowed : own, join(path, key));
                }
            }
        }
    }

    [[noreturn]] void unknown(const std::string& key, const toml::node& v,
                              const std::vector<std::string>& allowed, const std::string& path) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        const std::string guess = closest_name(key, allowed.data(), allowed.size());
        throw ConfigError(file_, line(&v), join(path, key),
                          "unknown key" +
                              (guess.empty() ? "" : " (did you mean '" + guess + "'?)") +
                              "; allowed here: " + list);
    }

    // Keys that are known but that no case used (e.g. `ior` for a mirror) are errors too.
    void report_unused(const toml::table& t, const std::string& path) {
        for (const auto& [k, v] : t) {
            const std::string key = join(path, std::string(k.str()));
            if (const toml::table* sub = v.as_table(); sub && usage_.used(&v)) {
                report_unused(*sub, key);
                continue;
            }
            if (const toml::array* arr = v.as_array(); arr && arr->is_array_of_tables()) {
                for (size_t i = 0; i < arr->size(); ++i)
                    report_unused(*(*arr)[i].as_table(), key + "[" + std::to_string(i) + "]");
                continue;
            }
            if (!usage_.used(&v))
                throw ConfigError(file_, line(&v), key,
                                  "is not used by any case (it does not apply to the settings "
                                  "around it, e.g. a material key the material type ignores)");
        }
    }

    const toml::table* section(const toml::table* t, const std::string& name) const {
        if (!t) return nullptr;
        const toml::node* n = t->get(name);
        return n ? n->as_table() : nullptr;
    }

    // A case's section, with the file's top-level section of the same name as its defaults.
    TableReader reader(const toml::table* case_table, const std::string& case_path,
                       const std::string& name) {
        return TableReader(section(case_table, name), join(case_path, name), section(&root_, name),
                           name, file_, usage_);
    }

    CaseConfig load_case(const toml::table* t, const std::string& path) {
        CaseConfig c;
        if (t) {
            TableReader named(t, path, nullptr, "", file_, usage_);
            c.name = named.any_string(kName.name);
        } else {
            TableReader top(&root_, "", nullptr, "", file_, usage_);
            std::string stem = file_.substr(file_.find_last_of('/') + 1);
            stem = stem.substr(0, stem.find('.'));
            c.name = top.has("name") ? top.any_string("name") : stem;
        }
        const auto start = std::chrono::steady_clock::now();
        c.ndf = read_ndf(reader(t, path, "ndf"));
        c.ndf_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        c.material = read_material(reader(t, path, "material"), reader(t, path, "spectrum"));
        TableReader beam = reader(t, path, "beam");
        if (beam.has(kThetaI.name)) c.theta_i_deg = beam.number_list(kThetaI);
        c.phi_i_deg = beam.number_list(kPhiI);
        // Each angle once, in order: a result file's axes are then checkable (sorted, no repeat).
        for (const auto& [key, sweep] :
             {std::pair{&kThetaI, &c.theta_i_deg}, {&kPhiI, &c.phi_i_deg}})
            for (size_t k = 1; k < sweep->size(); ++k)
                if (!((*sweep)[k] > (*sweep)[k - 1]))
                    beam.fail(key->name, "must increase, each angle once (" +
                                             shortest((*sweep)[k - 1]) + " then " +
                                             shortest((*sweep)[k]) + ")");
        TableReader sensor = reader(t, path, "sensor");
        c.sensor_cells = static_cast<int>(sensor.integer(kCells));
        TableReader trace = reader(t, path, "trace");
        c.trace = read_trace(trace);
        c.model = read_models(reader(t, path, "model"), c.material, c.ndf, c.trace.rays,
                              c.trace.max_bounces, c.trace.backend);
        TableReader surface = reader(t, path, "surface");
        c.surface = read_surface(surface, seed_, *c.ndf, c.trace.target.active());
        return c;
    }

    void check_names(const Config& cfg) {
        std::set<std::string> seen;
        for (size_t k = 0; k < cfg.cases.size(); ++k) {
            const std::string& n = cfg.cases[k].name;
            const std::string key = cfg.cases.size() > 1 || root_.get("case")
                                        ? "case[" + std::to_string(k) + "].name"
                                        : "name";
            const toml::node* node = nullptr;
            if (const toml::array* arr = root_["case"].as_array())
                node = (*arr)[k].as_table()->get("name");
            // An HDF5 group and a file name: "." and ".." are neither.
            if (n.empty() || n == "." || n == ".." ||
                n.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                    "0123456789_.-+") != std::string::npos)
                throw ConfigError(file_, line(node), key,
                                  "\"" + cut_text(n) +
                                      "\" is not allowed; use letters, digits and _ . - + (not "
                                      "\".\" or \"..\" alone)");
            if (!seen.insert(n).second)
                throw ConfigError(file_, line(node), key,
                                  "\"" + cut_text(n) + "\" names two cases");
        }
    }

    const toml::table& root_;
    std::string file_;
    UsageTracker usage_;
    std::uint64_t seed_ = 1;
};

std::string key_path(const KeyGroup& g, const Key& k) {
    return g.section.empty() ? k.name : g.section + "." + k.name;
}

} // namespace

bool CaseConfig::needs_surface() const {
    return std::any_of(model.models.begin(), model.models.end(),
                       [](const ModelChoice& m) { return m.needs_surface; });
}

void Config::require_beam(const std::string& command) const {
    for (size_t k = 0; k < cases.size(); ++k)
        if (cases[k].theta_i_deg.empty())
            throw ConfigError(path, -1,
                              cases.size() > 1 ? "case[" + std::to_string(k) + "].beam.theta_i"
                                               : "beam.theta_i",
                              "missing (" + command + " needs an incidence sweep); allowed " +
                                  kThetaI.range.describe() + " degrees");
}

std::vector<KeyGroup> config_key_groups() {
    std::vector<KeyGroup> groups{{"", "", "", {kSeed, kName, kCase}}};
    for (const KeyGroup& g : ndf_key_groups()) groups.push_back(g);
    for (const KeyGroup& g : material_key_groups()) groups.push_back(g);
    groups.push_back({"beam", "", "", {kThetaI, kPhiI}});
    groups.push_back({"sensor", "", "", {kCells}});
    for (const KeyGroup& g : model_key_groups()) groups.push_back(g);
    for (const KeyGroup& g : trace_key_groups()) groups.push_back(g);
    for (const KeyGroup& g : surface_key_groups()) groups.push_back(g);
    return groups;
}

std::string keys_markdown() {
    // One row per key; a key that several components declare alike (the roughness of the five
    // alpha families) is one row naming them all.
    struct Row {
        std::string key, owners, rest;
    };
    std::vector<Row> rows;
    for (const KeyGroup& g : config_key_groups())
        for (const Key& k : g.keys) {
            const std::string rest = " | " + k.type_text() + " | " + k.default_text() + " | " +
                                     k.meaning + (k.cite.empty() ? "" : " [" + k.cite + "]") +
                                     " |\n";
            const std::string owner = g.owner.empty() ? "" : "`" + g.owner + "`";
            auto same = std::find_if(rows.begin(), rows.end(), [&](const Row& r) {
                return r.key == key_path(g, k) && r.rest == rest && !r.owners.empty();
            });
            if (same != rows.end() && !owner.empty())
                same->owners += ", " + owner;
            else
                rows.push_back({key_path(g, k), owner, rest});
        }
    std::string out = "| key | for | type and range | default | meaning |\n|---|---|---|---|---|\n";
    for (const Row& r : rows) out += "| `" + r.key + "` | " + r.owners + r.rest;
    return out;
}

std::string keys_text() {
    std::string out;
    for (const KeyGroup& g : config_key_groups()) {
        out += "\n[" + (g.section.empty() ? std::string("top level") : g.section) + "]" +
               (g.owner.empty() ? "" : " " + g.owner) +
               (g.summary.empty() ? "" : ": " + g.summary) + "\n";
        for (const Key& k : g.keys) {
            out += "  " + key_path(g, k) + "\n      " + k.type_text() + "; default " +
                   k.default_text() + "\n      " + k.meaning +
                   (k.cite.empty() ? "" : " [" + k.cite + "]") + "\n";
        }
    }
    return out;
}

Config parse_config(const std::string& text, const std::string& path,
                    const std::vector<std::string>& overrides) {
    const ResultFloatMode mode; // the distributions' tables are computed here
    if (const std::string why = toml_limits_problem(text); !why.empty())
        throw ConfigError(path, -1, "", why);
    toml::table root;
    try {
        root = toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        throw ConfigError(path, static_cast<int>(e.source().begin.line), "",
                          "TOML syntax error: " + std::string(e.description()));
    }
    for (const auto& o : overrides) apply_override(root, o, path);
    Config cfg = Loader(root, path).load();
    cfg.path = path;
    cfg.text = text;
    cfg.overrides = overrides;
    std::ostringstream s;
    s << root;
    cfg.effective_toml = s.str();
    return cfg;
}

Config load_config(const std::string& path, const std::vector<std::string>& overrides) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ConfigError(path, -1, "", "cannot open the config file (missing or unreadable)");
    std::stringstream buffer;
    buffer << in.rdbuf();
    return parse_config(buffer.str(), path, overrides);
}

} // namespace gonio
