// SPDX-License-Identifier: BSD-3-Clause
#include "section.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

#include "camfollower/error.hpp"
#include "units.hpp"

namespace camfollower::config {

namespace {

// Echo at most a short, printable excerpt of user text in messages.
std::string excerpt(std::string_view s) { return detail::printable(s); }

std::string trim(std::string_view s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string_view::npos) return "";
    return std::string(s.substr(b, s.find_last_not_of(" \t") - b + 1));
}

}  // namespace

Section::Section(const toml::table& table, std::string path, std::shared_ptr<const std::string> origin)
    : table_(table), path_(std::move(path)), origin_(std::move(origin)) {}

std::vector<std::string> Section::keys() const {
    std::vector<std::string> out;
    for (auto&& [k, v] : table_) out.emplace_back(k.str());
    return out;
}

std::string Section::key_path(std::string_view key) const {
    // Keys are user text too (a quoted TOML key may hold anything): echoed printable and short.
    return path_.empty() ? detail::printable(key) : path_ + "." + detail::printable(key);
}

std::string Section::location(const toml::node* node) const {
    const toml::source_region& s = node ? node->source() : table_.source();
    return s.begin.line > 0 ? detail::concat(*origin_, ":", s.begin.line) : *origin_;
}

std::string Section::where(std::string_view key) const { return location(table_.get(key)) + ": " + key_path(key); }

void Section::fail(std::string_view key, const std::string& message) const { detail::fail(where(key), ": ", message); }

void Section::fail_here(const std::string& message) const { detail::fail(here(), ": ", message); }

namespace {

bool word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// The message with its quoted names ('rod', 'ground') blanked: a name is the user's, never a key. A
// quote opens after a non-word character only, so "the cam's" stays text.
std::string unquoted(std::string_view message) {
    std::string out(message);
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (out[i] != '\'' || (i > 0 && word_char(out[i - 1]))) continue;
        const std::size_t close = out.find('\'', i + 1);
        if (close == std::string::npos) break;
        std::fill(out.begin() + std::ptrdiff_t(i), out.begin() + std::ptrdiff_t(close) + 1, ' ');
        i = close;
    }
    return out;
}

// Where `word` first stands alone in `text` (npos if nowhere), skipping a kind word before a quoted
// name ("clearance 'gap'": the element, not its key `clearance`); `original` is `text` unblanked.
std::size_t find_word(const std::string& text, std::string_view original, const std::string& word) {
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
        const std::size_t end = at + word.size();
        if ((at > 0 && word_char(text[at - 1])) || (end < text.size() && word_char(text[end]))) continue;
        if (original.substr(end, 2) == " '") continue;
        return at;
    }
    return std::string::npos;
}

}  // namespace

void Section::fail_named(const std::string& message) const {
    const std::string text = unquoted(message);
    std::string best;
    std::size_t best_at = std::string::npos;
    for (auto&& [k, v] : table_) {
        const std::string key(k.str());
        std::string spaced = key;
        std::replace(spaced.begin(), spaced.end(), '_', ' ');
        for (const std::string& form : {key, spaced}) {
            const std::size_t at = find_word(text, message, form);
            // A one-letter key (a spring's a, b) only where the message starts: "a" is a word too.
            if (at == std::string::npos || (key.size() < 2 && at != 0)) continue;
            if (at < best_at || (at == best_at && key.size() > best.size())) best = key, best_at = at;
        }
    }
    if (best.empty()) fail_here(message);
    // "offset must ..." at the key offset reads "...offset: must ...".
    const std::string lead = best + " must ";
    fail(best, message.compare(0, lead.size(), lead) == 0 ? message.substr(best.size() + 1) : message);
}

std::string Section::here() const { return path_.empty() ? location(nullptr) : location(nullptr) + ": " + path_; }

const toml::node* Section::get(std::string_view key) const {
    const toml::node* n = table_.get(key);
    if (n) read_.emplace(key);
    return n;
}

const toml::node& Section::need(std::string_view key) const {
    const toml::node* n = get(key);
    if (!n) fail_here(detail::concat("the key '", key, "' is required here"));
    return *n;
}

double Section::quantity_of(const toml::node& node, std::string_view key, std::string_view si,
                            std::string_view unit) const {
    const auto bad = [&](const std::string& why) -> double {
        detail::fail(location(&node), ": ", key_path(key), ": ", why);
    };
    double v = 0.0;
    if (const auto x = node.value_exact<double>()) {
        v = *x;
    } else if (const auto i = node.value_exact<int64_t>()) {
        v = double(*i);
    } else if (const auto s = node.value_exact<std::string>()) {
        const std::string text = trim(*s);
        std::istringstream in(text);
        in.imbue(std::locale::classic());
        double number = 0.0;
        if (!(in >> number)) bad("'" + excerpt(*s) + "' is not a number or a \"<number> <unit>\" string");
        std::string rest;
        std::getline(in, rest);
        rest = trim(rest);
        if (rest.empty()) {
            v = number;
        } else {
            try {
                v = to_si(number, rest, si);
            } catch (const std::invalid_argument& e) {
                bad(e.what());
            }
        }
        if (!std::isfinite(v)) bad("'" + excerpt(*s) + "' is not finite");
        return v;
    } else {
        bad(detail::concat("must be a number (SI, ", quantity_kind(si).si, ") or a \"<number> <unit>\" string, got a ",
                           node.type()));
    }
    if (!unit.empty()) {
        try {
            v = to_si(v, unit, si);
        } catch (const std::invalid_argument& e) {
            bad(e.what());
        }
    }
    if (!std::isfinite(v)) bad("must be finite");
    return v;
}

double Section::quantity(std::string_view key, std::string_view si) const {
    return quantity_of(need(key), key, si, "");
}

double Section::quantity(std::string_view key, std::string_view si, double fallback) const {
    const toml::node* n = get(key);
    return n ? quantity_of(*n, key, si, "") : fallback;
}

std::vector<double> Section::quantities(std::string_view key, std::string_view si) const {
    return quantities(key, si, "");
}

std::vector<double> Section::quantities(std::string_view key, std::string_view si, std::string_view unit) const {
    const toml::node& n = need(key);
    const toml::array* a = n.as_array();
    if (!a) detail::fail(location(&n), ": ", key_path(key), ": must be an array of numbers");
    std::vector<double> out;
    out.reserve(a->size());
    for (std::size_t i = 0; i < a->size(); ++i)
        out.push_back(quantity_of(*a->get(i), detail::concat(key, "[", i, "]"), si, unit));
    return out;
}

long long Section::integer(std::string_view key, long long fallback, long long lo, long long hi) const {
    const toml::node* n = get(key);
    if (!n) return fallback;
    const auto i = n->value_exact<int64_t>();
    if (!i) fail(key, detail::concat("must be a whole number in [", lo, ", ", hi, "], got a ", n->type()));
    if (*i < lo || *i > hi) fail(key, detail::concat("must be in [", lo, ", ", hi, "], got ", *i));
    return *i;
}

namespace {

// The unit of a "<number> <unit>" string node ("" for a bare number or anything else).
std::string unit_of(const toml::node* n) {
    const auto s = n ? n->value_exact<std::string>() : std::nullopt;
    if (!s) return "";
    std::istringstream in(trim(*s));
    in.imbue(std::locale::classic());
    double number = 0.0;
    std::string rest;
    if (!(in >> number)) return "";
    std::getline(in, rest);
    return trim(rest);
}

}  // namespace

std::string Section::unit(std::string_view key) const { return unit_of(table_.get(key)); }

std::vector<std::string> Section::units(std::string_view key) const {
    std::vector<std::string> out;
    const toml::node* n = table_.get(key);
    if (const toml::array* a = n ? n->as_array() : nullptr)
        for (std::size_t i = 0; i < a->size(); ++i) out.push_back(unit_of(a->get(i)));
    return out;
}

bool Section::flag(std::string_view key, bool fallback) const {
    const toml::node* n = get(key);
    if (!n) return fallback;
    const auto b = n->value_exact<bool>();
    if (!b) fail(key, detail::concat("must be true or false, got a ", n->type()));
    return *b;
}

std::string Section::text(std::string_view key) const {
    const toml::node& n = need(key);
    const auto s = n.value_exact<std::string>();
    if (!s) detail::fail(location(&n), ": ", key_path(key), ": must be a string, got a ", n.type());
    return *s;
}

std::string Section::text(std::string_view key, std::string_view fallback) const {
    return has(key) ? text(key) : std::string(fallback);
}

std::vector<std::string> Section::texts(std::string_view key) const {
    const toml::node& n = need(key);
    const toml::array* a = n.as_array();
    if (!a) detail::fail(location(&n), ": ", key_path(key), ": must be an array of strings");
    std::vector<std::string> out;
    for (const toml::node& e : *a) {
        const auto s = e.value_exact<std::string>();
        if (!s) detail::fail(location(&e), ": ", key_path(key), ": must hold strings only, got a ", e.type());
        out.push_back(*s);
    }
    return out;
}

std::string Section::choice(std::string_view key, std::string_view fallback,
                            const std::vector<std::string_view>& allowed) const {
    const std::string v = text(key, fallback);
    std::string list;
    for (std::string_view a : allowed) {
        if (v == a) return v;
        list += std::string(list.empty() ? "\"" : ", \"") + std::string(a) + "\"";
    }
    fail(key, "must be one of " + list + ", got \"" + excerpt(v) + "\"");
}

std::optional<Section> Section::table(std::string_view key) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    const toml::table* t = n->as_table();
    if (!t) fail(key, detail::concat("must be a table, got a ", n->type()));
    return Section(*t, key_path(key), origin_);
}

std::vector<Section> Section::tables(std::string_view key) const {
    std::vector<Section> out;
    const toml::node* n = get(key);
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a) fail(key, detail::concat("must be an array of tables ([[", key, "]] blocks), got a ", n->type()));
    for (std::size_t i = 0; i < a->size(); ++i) {
        const toml::table* t = a->get(i)->as_table();
        if (!t) detail::fail(location(a->get(i)), ": ", key_path(key), "[", i, "]: must be a table");
        out.emplace_back(*t, detail::concat(key_path(key), "[", i, "]"), origin_);
    }
    return out;
}

std::vector<std::pair<std::string, Section>> Section::named_tables(std::string_view key) const {
    std::vector<std::pair<std::string, Section>> out;
    const std::optional<Section> parent = table(key);
    if (!parent) return out;
    for (auto&& [k, v] : parent->table_) {
        const std::string name(k.str());
        parent->read_.insert(name);
        const toml::table* t = v.as_table();
        if (!t) detail::fail(location(&v), ": ", parent->key_path(name), ": must be a table ([", key, ".", name, "])");
        out.emplace_back(name, Section(*t, parent->key_path(name), origin_));
    }
    return out;
}

void Section::finish(const std::vector<std::string_view>& known) const {
    for (auto&& [k, v] : table_) {
        if (read_.count(k.str())) continue;
        std::string list;
        for (std::string_view s : known) list += std::string(list.empty() ? "" : ", ") + std::string(s);
        const bool allowed = [&] {
            for (std::string_view s : known)
                if (s == k.str()) return true;
            return false;
        }();
        detail::fail(location(&v), ": ", key_path(k.str()), ": ",
                     allowed ? "is not used in this configuration (it does not apply here)"
                             : "unknown key" + (list.empty() ? std::string() : "; known here: " + list));
    }
}

std::string key_path_text(const std::vector<std::string>& parts) {
    std::string out;
    // A key after another part takes a dot; an index, and the first part after the elision, none.
    const auto add = [&](std::size_t i, bool first) {
        const std::string& p = parts[i];
        out += (!first && p.rfind('[', 0) != 0 ? "." : "") + detail::printable(p, 40);
    };
    if (parts.size() <= 6) {
        for (std::size_t i = 0; i < parts.size(); ++i) add(i, i == 0);
        return out;
    }
    for (std::size_t i = 0; i < 3; ++i) add(i, i == 0);
    out += detail::concat(" ... (", parts.size() - 5, " more) ... ");
    for (std::size_t i = parts.size() - 2; i < parts.size(); ++i) add(i, i == parts.size() - 2);
    return out;
}

void fail_nesting(const std::string& origin, std::size_t line, const std::vector<std::string>& parts) {
    detail::fail(line > 0 ? detail::concat(origin, ":", line) : origin, ": ", key_path_text(parts),
                 ": nested deeper than ", max_nesting, " levels of tables and arrays (a config needs fewer than 6)");
}

namespace {

// Depth-first over tables and arrays, refusing the first one below max_nesting levels; the recursion
// stops there, so it is bounded whatever the input.
void check_nesting(const toml::node& node, int depth, std::vector<std::string>& parts, const std::string& origin) {
    if (!node.is_table() && !node.is_array()) return;
    if (depth > max_nesting) fail_nesting(origin, node.source().begin.line, parts);
    if (const toml::table* t = node.as_table()) {
        for (auto&& [k, v] : *t) {
            parts.emplace_back(k.str());
            check_nesting(v, depth + 1, parts, origin);
            parts.pop_back();
        }
    } else {
        const toml::array& a = *node.as_array();
        for (std::size_t i = 0; i < a.size(); ++i) {
            parts.push_back(detail::concat("[", i, "]"));
            check_nesting(*a.get(i), depth + 1, parts, origin);
            parts.pop_back();
        }
    }
}

}  // namespace

toml::table parse_toml(std::string_view text, const std::string& origin) {
    toml::table root;
    try {
        root = toml::parse(text, origin);
    } catch (const toml::parse_error& e) {
        const toml::source_position p = e.source().begin;
        detail::fail(origin, ":", p.line, ":", p.column, ": TOML syntax: ", e.description());
    }
    std::vector<std::string> parts;
    check_nesting(root, 0, parts, origin);
    return root;
}

}  // namespace camfollower::config
