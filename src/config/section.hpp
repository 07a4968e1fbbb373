// SPDX-License-Identifier: BSD-3-Clause
// Reading one table of a parsed config: typed values with units, and errors that name the file, the
// line and the key path ("cam.toml:12: contact[1].follower.base_radius: ..."). Every key read is
// marked; finish() refuses the keys nobody read, so a misspelt or misplaced key never passes silently.
#pragma once

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

namespace camfollower::config {

class Section {
public:
    // `path` is the key path of this table ("" for the root); `origin` the file name for messages.
    Section(const toml::table& table, std::string path, std::shared_ptr<const std::string> origin);

    const std::string& path() const { return path_; }
    const std::string& origin() const { return *origin_; }
    bool has(std::string_view key) const { return table_.contains(key); }
    std::vector<std::string> keys() const;

    // Quantities: a number in SI, or "<number> <unit>" with a unit of kind `si` (units.hpp).
    double quantity(std::string_view key, std::string_view si) const;
    double quantity(std::string_view key, std::string_view si, double fallback) const;
    std::vector<double> quantities(std::string_view key, std::string_view si) const;
    std::vector<double> quantities(std::string_view key, std::string_view si, std::string_view unit) const;
    // A whole number in [lo, hi] (checked before any conversion).
    long long integer(std::string_view key, long long fallback, long long lo, long long hi) const;
    bool flag(std::string_view key, bool fallback) const;
    // The unit written in a "<number> <unit>" value ("" for a bare number or an absent key).
    std::string unit(std::string_view key) const;
    // The unit of each element of an array value (as unit(); empty when the key is absent or no array).
    std::vector<std::string> units(std::string_view key) const;
    std::string text(std::string_view key) const;
    std::string text(std::string_view key, std::string_view fallback) const;
    std::vector<std::string> texts(std::string_view key) const;
    // One of `allowed` (the message lists them).
    std::string choice(std::string_view key, std::string_view fallback,
                       const std::vector<std::string_view>& allowed) const;
    std::optional<Section> table(std::string_view key) const;
    // An array of tables ([[key]] blocks, or an array of inline tables); empty when absent.
    std::vector<Section> tables(std::string_view key) const;
    // Named sub-tables of a table: [program.a], [program.b] -> ("a", Section), ("b", Section).
    std::vector<std::pair<std::string, Section>> named_tables(std::string_view key) const;

    // Refuse keys that were not read: "unknown key ...; known here: ...".
    void finish(const std::vector<std::string_view>& known) const;

    [[noreturn]] void fail(std::string_view key, const std::string& message) const;
    [[noreturn]] void fail_here(const std::string& message) const;
    // A model builder's message (it names its parameter, "stiffness of 'rod' must be ..."), located at
    // the key of this table it names first (underscores may be spaces; quoted names and a kind word
    // before one, "clearance 'gap'", do not count), else at the table itself.
    [[noreturn]] void fail_named(const std::string& message) const;
    std::string where(std::string_view key) const;  // "file:line: path.key"
    std::string here() const;                       // "file:line: path" of the table itself

private:
    const toml::node* get(std::string_view key) const;  // marks the key read; nullptr if absent
    const toml::node& need(std::string_view key) const;
    double quantity_of(const toml::node& node, std::string_view key, std::string_view si, std::string_view unit) const;
    std::string key_path(std::string_view key) const;
    std::string location(const toml::node* node) const;

    const toml::table& table_;
    std::string path_;
    std::shared_ptr<const std::string> origin_;
    mutable std::set<std::string, std::less<>> read_;
};

// Tables and arrays nested deeper than this are refused, by every route into the reader (a file, a
// Python dict): a config needs fewer than 6 levels, and the bound keeps every recursive walk over a
// config (conversions to and from Python, copies) far from the stack's end and ends a cyclic dict.
inline constexpr int max_nesting = 64;

// A key path as messages show it ("contact[0].follower.offset"): each part printable and short, a
// path of more than 6 parts shown by its first 3 and last 2. Parts are keys, or "[i]" for an index.
std::string key_path_text(const std::vector<std::string>& parts);

// "origin[:line]: path: nested deeper than 64 levels ...": the refusal of a too deep value.
[[noreturn]] void fail_nesting(const std::string& origin, std::size_t line, const std::vector<std::string>& parts);

// Parse TOML text (a UTF-8 byte order mark is skipped, as toml++ does); a syntax error (duplicate
// keys included) becomes std::invalid_argument "origin:line:column: message", a table nested deeper
// than max_nesting "origin:line: key.path: nested deeper than ...".
toml::table parse_toml(std::string_view text, const std::string& origin);

}  // namespace camfollower::config
