#include "core/table_reader.h"

#include "core/config_error.h"
#include "core/message.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace gonio {

namespace {
std::string number_text(double v) {
    return shortest(v);
}
std::string type_name(const toml::node& n) {
    switch (n.type()) {
    case toml::node_type::string:
        return "a string";
    case toml::node_type::integer:
        return "an integer";
    case toml::node_type::floating_point:
        return "a number";
    case toml::node_type::boolean:
        return "a boolean";
    case toml::node_type::array:
        return "an array";
    case toml::node_type::table:
        return "a table";
    default:
        return "a date or time";
    }
}
} // namespace

TableReader::TableReader(const toml::table* section, std::string section_path,
                         const toml::table* defaults, std::string defaults_path, std::string file,
                         UsageTracker& usage)
    : section_(section), section_path_(std::move(section_path)), defaults_(defaults),
      defaults_path_(std::move(defaults_path)), file_(std::move(file)), usage_(usage) {}

TableReader::Found TableReader::find(const std::string& key) const {
    if (section_)
        if (const toml::node* n = section_->get(key)) return {n, true};
    if (defaults_)
        if (const toml::node* n = defaults_->get(key)) return {n, false};
    return {};
}

bool TableReader::has(const std::string& key) const {
    return find(key).node != nullptr;
}
bool TableReader::has_own(const std::string& key) const {
    return section_ && section_->get(key) != nullptr;
}
TableReader TableReader::own() const {
    return TableReader(section_, section_path_, nullptr, defaults_path_, file_, usage_);
}
bool TableReader::is_string(const std::string& key) const {
    const Found f = find(key);
    return f.node && f.node->is_string();
}

std::string TableReader::key_path(const std::string& key) const {
    const Found f = find(key);
    const std::string& prefix =
        (f.node && !f.in_section) || !section_ ? defaults_path_ : section_path_;
    return prefix.empty() ? key : prefix + "." + key;
}

int TableReader::line_of(const std::string& key) const {
    const Found f = find(key);
    if (f.node) return static_cast<int>(f.node->source().begin.line);
    if (section_) return static_cast<int>(section_->source().begin.line);
    if (defaults_) return static_cast<int>(defaults_->source().begin.line);
    return 0;
}

void TableReader::fail(const std::string& key, const std::string& problem) const {
    int line = line_of(key);
    // A key given neither here nor in the defaults: point at the file, not the command line.
    if (line == 0 && !find(key).node) line = 1;
    throw ConfigError(file_, line, key_path(key), problem);
}

const toml::node& TableReader::require(const std::string& key) const {
    const Found f = find(key);
    if (!f.node) fail(key, "missing (required)");
    usage_.mark(f.node);
    return *f.node;
}

double TableReader::as_number(const toml::node& n, const std::string& key,
                              const Range& range) const {
    const std::optional<double> v = n.value<double>();
    if (!v || !(n.is_integer() || n.is_floating_point()))
        fail(key, "must be a number, got " + type_name(n) + "; allowed " + range.describe());
    if (!range.contains(*v))
        fail(key, "value " + number_text(*v) + " is out of range; allowed " + range.describe());
    return *v;
}

std::string TableReader::any_string(const std::string& key) {
    const toml::node& n = require(key);
    if (!n.is_string()) fail(key, "must be a string, got " + type_name(n));
    return *n.value<std::string>();
}

bool TableReader::boolean(const std::string& key, std::optional<bool> fallback) {
    if (!has(key) && fallback) return *fallback;
    const toml::node& n = require(key);
    if (!n.is_boolean()) fail(key, "must be true or false, got " + type_name(n));
    return *n.value<bool>();
}

std::string TableReader::string(const std::string& key, const std::vector<std::string>& allowed,
                                std::optional<std::string> fallback) {
    if (!has(key) && fallback) return *fallback;
    const std::string v = any_string(key);
    std::string list;
    for (const auto& a : allowed) {
        if (a == v) return v;
        list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
    }
    const std::string guess = closest_name(v, allowed.data(), allowed.size());
    fail(key, "\"" + cut_text(v) + "\" is not allowed" +
                  (guess.empty() ? "" : " (did you mean \"" + guess + "\"?)") +
                  "; allowed: " + list);
}

std::vector<std::string>
TableReader::string_list(const std::string& key, const std::vector<std::string>& allowed,
                         std::optional<std::vector<std::string>> fallback) {
    if (!has(key) && fallback) return *fallback;
    const toml::node& n = require(key);
    if (n.is_string()) return {string(key, allowed)};
    const toml::array* arr = n.as_array();
    if (!arr) fail(key, "must be a string or an array of strings");
    std::vector<std::string> out;
    for (const toml::node& e : *arr) {
        const auto v = e.value<std::string>();
        if (!v) fail(key, "must be a string or an array of strings");
        if (std::find(allowed.begin(), allowed.end(), *v) == allowed.end()) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
            const std::string guess = closest_name(*v, allowed.data(), allowed.size());
            fail(key, "\"" + cut_text(*v) + "\" is not allowed" +
                          (guess.empty() ? "" : " (did you mean \"" + guess + "\"?)") +
                          "; allowed: " + list);
        }
        if (std::find(out.begin(), out.end(), *v) != out.end())
            fail(key, "names \"" + cut_text(*v) + "\" twice");
        out.push_back(*v);
    }
    return out;
}

double TableReader::number(const std::string& key, const Range& range,
                           std::optional<double> fallback) {
    if (!has(key) && fallback) return *fallback;
    return as_number(require(key), key, range);
}

long long TableReader::integer(const std::string& key, const Range& range,
                               std::optional<long long> fallback) {
    if (!has(key) && fallback) return *fallback;
    const toml::node& n = require(key);
    if (!n.is_integer())
        fail(key, "must be an integer, got " + type_name(n) + "; allowed " + range.describe());
    const long long v = *n.value<long long>();
    if (!range.contains(static_cast<double>(v)))
        fail(key, "value " + std::to_string(v) + " is out of range; allowed " + range.describe());
    return v;
}

std::vector<double> TableReader::number_list(const std::string& key, const Range& range,
                                             std::optional<std::vector<double>> fallback) {
    if (!has(key) && fallback) return *fallback;
    const toml::node& n = require(key);
    std::vector<double> out;
    if (const toml::array* a = n.as_array()) {
        if (a->empty()) fail(key, "must not be an empty array");
        for (const toml::node& e : *a) out.push_back(as_number(e, key, range));
        return out;
    }
    if (const toml::table* t = n.as_table()) {
        // A range table: {start, stop, step} or {start, stop, count}, stop included.
        TableReader sub(t, key_path(key), nullptr, "", file_, usage_);
        const double start = sub.number("start", range);
        const double stop = sub.number("stop", range);
        const bool by_count = sub.has("count");
        if (by_count == sub.has("step"))
            fail(key, "a range table needs start, stop and exactly one of step or count");
        if (by_count) {
            const long long count = sub.integer("count", {1, 1e6});
            for (long long k = 0; k < count; ++k)
                out.push_back(count == 1 ? start : start + (stop - start) * k / (count - 1));
        } else {
            const double step = sub.number("step", {0, 1e9, true, false});
            if (stop < start) fail(key, "a range table needs stop >= start");
            const long long count =
                static_cast<long long>(std::floor((stop - start) / step + 1e-9)) + 1;
            if (count > 1000000) fail(key, "a range table may expand to at most 1000000 values");
            for (long long k = 0; k < count; ++k) out.push_back(start + step * k);
        }
        for (const auto& [k, v] : *t)
            if (!usage_.used(&v))
                throw ConfigError(file_, static_cast<int>(v.source().begin.line),
                                  key_path(key) + "." + std::string(k.str()),
                                  "unknown key (allowed: start, stop, step, count)");
        return out;
    }
    out.push_back(as_number(n, key, range));
    return out;
}

TableReader TableReader::table(const std::string& key) {
    const toml::node& n = require(key);
    if (!n.is_table())
        fail(key, "must be a table, e.g. " + key + " = { type = \"ggx\", alpha = 0.3 }");
    return TableReader(n.as_table(), key_path(key), nullptr, "", file_, usage_);
}

std::vector<TableReader> TableReader::table_list(const std::string& key) {
    const toml::node& n = require(key);
    const toml::array* arr = n.as_array();
    if (!arr || arr->empty() || !arr->is_array_of_tables())
        fail(key, "must be a non-empty array of tables, e.g. [{ type = \"ggx\", alpha = 0.3 }]");
    std::vector<TableReader> out;
    const std::string path = key_path(key);
    for (size_t i = 0; i < arr->size(); ++i)
        out.emplace_back((*arr)[i].as_table(), path + "[" + std::to_string(i) + "]", nullptr, "",
                         file_, usage_);
    return out;
}

void TableReader::allow_only(const std::vector<std::string>& allowed) const {
    if (!section_) return;
    for (const auto& [k, v] : *section_) {
        const std::string key(k.str());
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        const std::string guess = closest_name(key, allowed.data(), allowed.size());
        throw ConfigError(file_, static_cast<int>(v.source().begin.line), section_path_ + "." + key,
                          "unknown key" +
                              (guess.empty() ? "" : " (did you mean '" + guess + "'?)") +
                              "; allowed here: " + list);
    }
}

double TableReader::number(const Key& k) {
    return number(k.name, k.range, k.number_default);
}
long long TableReader::integer(const Key& k) {
    std::optional<long long> fallback;
    if (k.number_default) fallback = static_cast<long long>(*k.number_default);
    return integer(k.name, k.range, fallback);
}
std::vector<double> TableReader::number_list(const Key& k) {
    return number_list(k.name, k.range, k.numbers_default);
}
std::string TableReader::string(const Key& k) {
    if (k.choices.empty()) {
        if (!has(k.name) && k.string_default) return *k.string_default;
        return any_string(k.name);
    }
    return string(k.name, k.choices, k.string_default);
}
std::vector<std::string> TableReader::string_list(const Key& k) {
    return string_list(k.name, k.choices, k.strings_default);
}
bool TableReader::boolean(const Key& k) {
    return boolean(k.name, k.bool_default);
}

std::string TableReader::path(const Key& k) {
    std::string p = any_string(k.name);
    if (!p.empty() && p[0] != '/') {
        const size_t slash = file_.find_last_of('/');
        if (slash != std::string::npos) p = file_.substr(0, slash + 1) + p;
    }
    if (!std::ifstream(p)) fail(k.name, "cannot open " + p);
    return p;
}

void TableReader::allow_only(const std::vector<const std::vector<Key>*>& groups) const {
    std::vector<std::string> names;
    for (const auto* g : groups)
        for (const Key& k : *g)
            if (std::find(names.begin(), names.end(), k.name) == names.end())
                names.push_back(k.name);
    allow_only(names);
}

} // namespace gonio
