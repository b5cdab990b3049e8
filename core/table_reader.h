#pragma once
// Typed, range-checked reads from one section of a TOML config, with its defaults.
//
// A case's section (e.g. [[case]] ... ndf = {...}) is read first and the file's top-level section
// of the same name supplies defaults. Every key read is marked as used; UsageTracker then reports
// any key no case used, so a misspelled or misplaced key never passes silently.
#include "core/config_key.h"

#include <optional>
#include <set>
#include <string>
#include <toml++/toml.h>
#include <vector>

namespace gonio {

class UsageTracker {
  public:
    void mark(const toml::node* n) { used_.insert(n); }
    bool used(const toml::node* n) const { return used_.count(n) > 0; }

  private:
    std::set<const toml::node*> used_;
};

class TableReader {
  public:
    // `section` and `defaults` may be null. Paths are the keys' prefixes in messages
    // ("case[1].ndf", "ndf").
    TableReader(const toml::table* section, std::string section_path, const toml::table* defaults,
                std::string defaults_path, std::string file, UsageTracker& usage);

    bool has(const std::string& key) const;
    // True if the case's own section gives the key (not only the defaults).
    bool has_own(const std::string& key) const;
    // The same reader without the defaults: for keys that must be given together.
    TableReader own() const;
    // The message key and line of a key (where it was found, else the section).
    std::string key_path(const std::string& key) const;
    int line_of(const std::string& key) const;

    std::string string(const std::string& key, const std::vector<std::string>& allowed,
                       std::optional<std::string> fallback = std::nullopt);
    std::string any_string(const std::string& key);
    // A string or an array of strings, each one of `allowed`, without repeats.
    std::vector<std::string> string_list(const std::string& key,
                                         const std::vector<std::string>& allowed,
                                         std::optional<std::vector<std::string>> fallback);
    bool boolean(const std::string& key, std::optional<bool> fallback = std::nullopt);
    double number(const std::string& key, const Range& range,
                  std::optional<double> fallback = std::nullopt);
    long long integer(const std::string& key, const Range& range,
                      std::optional<long long> fallback = std::nullopt);
    // A number, an array of numbers, or a range table {start, stop, step} / {start, stop, count}
    // (stop included); every value must be in `range`.
    std::vector<double> number_list(const std::string& key, const Range& range,
                                    std::optional<std::vector<double>> fallback = std::nullopt);
    bool is_string(const std::string& key) const;

    // Reads of a declared key: its range or choices, its default (a key without one is required).
    double number(const Key& key);
    long long integer(const Key& key);
    std::vector<double> number_list(const Key& key);
    std::string string(const Key& key);
    std::vector<std::string> string_list(const Key& key);
    bool boolean(const Key& key);
    // A path relative to the config file's directory; the file must exist.
    std::string path(const Key& key);
    TableReader table(const Key& key) { return table(key.name); }
    std::vector<TableReader> table_list(const Key& key) { return table_list(key.name); }
    // Rejects keys of this reader's own section that none of `groups` declares.
    void allow_only(const std::vector<const std::vector<Key>*>& groups) const;
    // The config file these keys come from.
    const std::string& file() const { return file_; }
    // A nested table (inline or not) as a reader of its own, without defaults; marks it used.
    TableReader table(const std::string& key);
    // Each table of an array of tables (e.g. a mixture's components), at least one.
    std::vector<TableReader> table_list(const std::string& key);
    // Rejects any key of this reader's own section not in `allowed`, suggesting the closest.
    void allow_only(const std::vector<std::string>& allowed) const;

    [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

  private:
    struct Found {
        const toml::node* node = nullptr;
        bool in_section = false;
    };
    Found find(const std::string& key) const;
    const toml::node& require(const std::string& key) const;
    double as_number(const toml::node& n, const std::string& key, const Range& range) const;

    const toml::table* section_;
    std::string section_path_;
    const toml::table* defaults_;
    std::string defaults_path_;
    std::string file_;
    UsageTracker& usage_;
};

} // namespace gonio
