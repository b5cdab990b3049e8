#include "core/config_key.h"

#include <cmath>
#include <cstdio>

namespace gonio {

bool Range::contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (lo_open ? !(v > lo) : !(v >= lo)) return false;
    if (hi_open ? !(v < hi) : !(v <= hi)) return false;
    return true;
}

std::string Range::describe() const {
    return std::string(lo_open ? "(" : "[") + shortest(lo) + ", " + shortest(hi) +
           (hi_open ? ")" : "]");
}

namespace {
Key make(std::string name, KeyKind kind, std::string meaning) {
    Key k;
    k.name = std::move(name);
    k.kind = kind;
    k.meaning = std::move(meaning);
    return k;
}
std::string quoted_list(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& c : v) s += (s.empty() ? "" : ", ") + ("\"" + c + "\"");
    return s;
}
std::string number_list(const std::vector<double>& v) {
    std::string s;
    for (double x : v) s += (s.empty() ? "" : ", ") + shortest(x);
    return v.size() == 1 ? s : "[" + s + "]";
}
} // namespace

Key Key::number(std::string name, Range range, std::string meaning) {
    Key k = make(std::move(name), KeyKind::number, std::move(meaning));
    k.range = range;
    return k;
}
Key Key::integer(std::string name, Range range, std::string meaning) {
    Key k = make(std::move(name), KeyKind::integer, std::move(meaning));
    k.range = range;
    return k;
}
Key Key::numbers(std::string name, Range range, std::string meaning) {
    Key k = make(std::move(name), KeyKind::numbers, std::move(meaning));
    k.range = range;
    return k;
}
Key Key::string(std::string name, std::vector<std::string> choices, std::string meaning) {
    Key k = make(std::move(name), KeyKind::string, std::move(meaning));
    k.choices = std::move(choices);
    return k;
}
Key Key::strings(std::string name, std::vector<std::string> choices, std::string meaning) {
    Key k = make(std::move(name), KeyKind::strings, std::move(meaning));
    k.choices = std::move(choices);
    return k;
}
Key Key::boolean(std::string name, std::string meaning) {
    return make(std::move(name), KeyKind::boolean, std::move(meaning));
}
Key Key::path(std::string name, std::string meaning) {
    return make(std::move(name), KeyKind::path, std::move(meaning));
}
Key Key::table(std::string name, std::string meaning) {
    return make(std::move(name), KeyKind::table, std::move(meaning));
}
Key Key::tables(std::string name, std::string meaning) {
    return make(std::move(name), KeyKind::tables, std::move(meaning));
}

Key Key::fallback(double v) const {
    Key k = *this;
    k.number_default = v;
    return k;
}
Key Key::fallback(std::string v) const {
    Key k = *this;
    k.string_default = std::move(v);
    return k;
}
Key Key::fallback(bool v) const {
    Key k = *this;
    k.bool_default = v;
    return k;
}
Key Key::fallback(std::vector<double> v) const {
    Key k = *this;
    k.numbers_default = std::move(v);
    return k;
}
Key Key::fallback(std::vector<std::string> v) const {
    Key k = *this;
    k.strings_default = std::move(v);
    return k;
}
Key Key::note_default(std::string text) const {
    Key k = *this;
    k.default_note = std::move(text);
    return k;
}
Key Key::in_unit(std::string u) const {
    Key k = *this;
    k.unit = std::move(u);
    return k;
}
Key Key::cited(std::string c) const {
    Key k = *this;
    k.cite = std::move(c);
    return k;
}
Key Key::noting(std::string n) const {
    Key k = *this;
    k.range_note = std::move(n);
    return k;
}

bool Key::required() const {
    return !number_default && !string_default && !bool_default && !numbers_default &&
           !strings_default && default_note.empty();
}

std::string Key::type_text() const {
    const std::string unit_text = unit.empty() ? "" : " " + unit;
    std::string s;
    switch (kind) {
    case KeyKind::number:
        s = "number in " + range.describe() + unit_text;
        break;
    case KeyKind::integer:
        s = "integer in " + range.describe();
        break;
    case KeyKind::numbers:
        s = "number or array in " + range.describe() + unit_text;
        break;
    case KeyKind::string:
        s = choices.empty() ? "string" : "one of " + quoted_list(choices);
        break;
    case KeyKind::strings:
        s = "string or array of " + quoted_list(choices);
        break;
    case KeyKind::boolean:
        s = "boolean";
        break;
    case KeyKind::path:
        s = "path (relative to the config)";
        break;
    case KeyKind::table:
        s = "table";
        break;
    case KeyKind::tables:
        s = "array of tables";
        break;
    }
    return range_note.empty() ? s : s + "; " + range_note;
}

std::string Key::default_text() const {
    if (!default_note.empty()) return default_note;
    if (number_default) return shortest(*number_default);
    if (string_default) return "\"" + *string_default + "\"";
    if (bool_default) return *bool_default ? "true" : "false";
    if (numbers_default) return number_list(*numbers_default);
    if (strings_default) return strings_default->empty() ? "[]" : quoted_list(*strings_default);
    return "—";
}

} // namespace gonio
