#include "gonio/config/overrides.h"

#include "core/config_error.h"
#include "core/toml_limits.h"

#include <sstream>
#include <vector>

namespace gonio {

namespace {
std::vector<std::string> split_path(const std::string& path) {
    std::vector<std::string> parts;
    std::string cur;
    for (char ch : path) {
        if (ch == '.') {
            parts.push_back(cur);
            cur.clear();
        } else {
            cur += ch;
        }
    }
    parts.push_back(cur);
    return parts;
}

bool is_index(const std::string& s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}
} // namespace

void apply_override(toml::table& root, const std::string& assignment, const std::string& file) {
    const size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        throw ConfigError(file, 0, assignment, "--set expects key.path=value");
    const std::string path = assignment.substr(0, eq);
    const std::string text = assignment.substr(eq + 1);
    if (const std::string why = toml_limits_problem(assignment); !why.empty())
        throw ConfigError(file, 0, "", "--set: " + why);
    const std::vector<std::string> parts = split_path(path);
    if (parts.size() >= size_t(kMaxTomlDepth))
        throw ConfigError(file, 0, path,
                          "--set: a key of more than " + std::to_string(kMaxTomlDepth) + " parts");
    for (const auto& p : parts)
        if (p.empty()) throw ConfigError(file, 0, path, "--set has an empty key segment");

    // The value: TOML if it parses, else a bare string.
    toml::table holder;
    try {
        holder = toml::parse("value = " + text);
    } catch (const toml::parse_error&) {
        holder = toml::table{{"value", text}};
    }
    toml::node* value = holder.get("value");

    toml::table* table = &root;
    for (size_t i = 0; i + 1 < parts.size(); ++i) {
        toml::node* next = table->get(parts[i]);
        if (!next) {
            table->insert(parts[i], toml::table{});
            next = table->get(parts[i]);
        }
        if (toml::array* arr = next->as_array()) {
            // An array of tables ([[case]]): the next segment picks an element.
            if (i + 2 >= parts.size())
                throw ConfigError(file, 0, path, "--set cannot replace a whole array of tables");
            // A name may itself contain dots ("beckmann_0.5"): try the longest match first.
            const size_t first = ++i;
            std::string pick = parts[first];
            toml::table* chosen = nullptr;
            if (is_index(pick)) {
                const size_t k = std::stoul(pick);
                if (k < arr->size()) chosen = (*arr)[k].as_table();
            }
            for (size_t last = parts.size() - 2; !chosen && last >= first; --last) {
                std::string name = parts[first];
                for (size_t j = first + 1; j <= last; ++j) name += "." + parts[j];
                for (auto& e : *arr)
                    if (toml::table* t = e.as_table())
                        if (auto n = (*t)["name"].value<std::string>(); n && *n == name) {
                            chosen = t;
                            i = last;
                        }
            }
            if (!chosen)
                throw ConfigError(file, 0, path,
                                  "no element '" + pick + "' in '" + parts[first - 1] +
                                      "' (use an index from 0 to " +
                                      std::to_string(arr->size() - 1) + " or a case name)");
            table = chosen;
            continue;
        }
        table = next->as_table();
        if (!table) throw ConfigError(file, 0, path, "'" + parts[i] + "' is not a table");
    }
    value->visit([&](auto&& v) { table->insert_or_assign(parts.back(), std::move(v)); });
}

} // namespace gonio
