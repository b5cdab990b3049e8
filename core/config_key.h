#pragma once
// One configuration key as a component declares it: name, kind, allowed range or choices,
// default, a one-line meaning and the paper it comes from. The same object is what the component
// reads with (TableReader::number(key), ...), what unknown-key checks and "did you mean" use,
// what `gonio keys` lists and what docs/configuration.md's table is generated from, so the
// schema exists once.
#include "core/number_text.h"

#include <optional>
#include <string>
#include <vector>

namespace gonio {

// Closed/open numeric interval used in checks and in the error text ("allowed (0, 100]").
struct Range {
    double lo = 0, hi = 0;
    bool lo_open = false, hi_open = false;
    bool contains(double v) const;
    std::string describe() const;
};

enum class KeyKind {
    number,  // a number in `range`
    integer, // an integer in `range`
    numbers, // a number, an array of numbers, or a range table {start, stop, step|count}
    string,  // one of `choices` (any string when empty)
    strings, // a string or an array of strings, each one of `choices`
    boolean, // true or false
    path,    // a file path, relative to the config file
    table,   // a nested table (e.g. an NDF inside a blend)
    tables,  // an array of nested tables
};

struct Key {
    std::string name;
    KeyKind kind = KeyKind::number;
    std::string meaning;              // one line, for `gonio keys` and docs/configuration.md
    Range range{};                    // number, integer, numbers
    std::vector<std::string> choices; // string, strings
    std::optional<double> number_default;
    std::optional<std::string> string_default;
    std::optional<bool> bool_default;
    std::optional<std::vector<double>> numbers_default;
    std::optional<std::vector<std::string>> strings_default;
    std::string default_note; // a default that is not a constant ("`seed`", "`trace.rays`")
    std::string unit;         // shown with the range: "degrees", "nm", "per rad", ...
    std::string cite;         // "R19 Eq. 11"
    std::string range_note;   // what the range cannot say ("p q >= 2")

    // Constructors of each kind; the setters below chain.
    static Key number(std::string name, Range range, std::string meaning);
    static Key integer(std::string name, Range range, std::string meaning);
    static Key numbers(std::string name, Range range, std::string meaning);
    static Key string(std::string name, std::vector<std::string> choices, std::string meaning);
    static Key strings(std::string name, std::vector<std::string> choices, std::string meaning);
    static Key boolean(std::string name, std::string meaning);
    static Key path(std::string name, std::string meaning);
    static Key table(std::string name, std::string meaning);
    static Key tables(std::string name, std::string meaning);

    Key fallback(double v) const;
    Key fallback(std::string v) const;
    Key fallback(const char* v) const { return fallback(std::string(v)); }
    Key fallback(bool v) const;
    Key fallback(std::vector<double> v) const;
    Key fallback(std::vector<std::string> v) const;
    Key note_default(std::string text) const; // the default, described
    Key in_unit(std::string u) const;
    Key cited(std::string c) const;
    Key noting(std::string n) const;

    bool required() const; // no default of any kind
    // For listings: "number in [0, 90) degrees", "one of "a", "b"", ...
    std::string type_text() const;
    std::string default_text() const; // "—" when required
};

// A group of keys with a name: a section's common keys, or one registered component's own keys
// (`owner` is then the component's name, e.g. the NDF family "ggx").
struct KeyGroup {
    std::string section; // "ndf", "material", "trace", ... ("" for the top level)
    std::string owner;   // "" for keys every case of the section reads
    std::string summary; // one line: what the owner is
    std::vector<Key> keys;
};

} // namespace gonio
