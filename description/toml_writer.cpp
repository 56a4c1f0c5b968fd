#include "description/toml_writer.hpp"

#include <algorithm>
#include <charconv>
#include <sstream>

namespace description {
namespace {

// Strings as basic strings (with escapes), never as literal ones: a
// literal string cannot hold its own quotes, and toml++ 3.3 would write a
// text holding ''' as a literal multi-line string all the same.
constexpr auto string_flags = toml::format_flags::allow_multi_line_strings | toml::format_flags::allow_unicode_strings;

void write_number(std::ostream& out, double v) {
    char text[40];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, v);  // the shortest that reads back the same
    std::string s(text, end);
    if (s.find_first_of(".eni") == std::string::npos) s += ".0";  // a float, not an integer ("inf", "nan" stay)
    out << s;
}

void write_value(std::ostream& out, const toml::node& v) {
    if (const auto* s = v.as_string()) {
        // TOML drops a line break right after a multi-line string's """:
        // a text that begins with one is written on one line, escaped.
        const std::string& text = s->get();
        const bool leading_break = !text.empty() && (text[0] == '\n' || text.compare(0, 2, "\r\n") == 0);
        out << toml::toml_formatter{*s, leading_break ? toml::format_flags::allow_unicode_strings : string_flags};
    } else if (const auto* f = v.as_floating_point()) {
        write_number(out, f->get());
    } else if (const auto* i = v.as_integer()) {
        out << i->get();
    } else if (const auto* b = v.as_boolean()) {
        out << (b->get() ? "true" : "false");
    } else if (const auto* a = v.as_array()) {
        out << "[";
        for (std::size_t k = 0; k < a->size(); ++k) {
            out << (k ? ", " : "");
            write_value(out, *a->get(k));
        }
        out << "]";
    } else if (const auto* t = v.as_table()) {
        out << "{";
        bool first = true;
        for (const auto& [key, value] : *t) {
            out << (first ? "" : ", ") << toml_key(std::string(key.str())) << " = ";
            write_value(out, value);
            first = false;
        }
        out << "}";
    } else {
        // Dates and times: no description holds them, but toml++ writes them right.
        v.visit([&](const auto& n) { out << toml::toml_formatter{n}; });
    }
}

// The keys of `t`: those of `first` in that order, then the others.
std::vector<std::string> ordered(const toml::table& t, const std::vector<std::string>& first) {
    std::vector<std::string> keys;
    for (const auto& k : first)
        if (t.contains(k)) keys.push_back(k);
    for (const auto& [k, v] : t)
        if (std::find(keys.begin(), keys.end(), std::string(k.str())) == keys.end()) keys.emplace_back(k.str());
    return keys;
}

void write_pair(std::ostream& out, const std::string& key, const toml::node& value) {
    out << toml_key(key) << " = ";
    write_value(out, value);
    out << "\n";
}

void write_section(std::ostream& out, const std::string& name, const toml::table& t, const std::vector<std::string>& first) {
    std::vector<std::string> tables;  // arrays of tables, after the keys
    out << "\n[" << toml_key(name) << "]\n";
    for (const auto& key : ordered(t, first)) {
        const toml::node& v = *t.get(key);
        if (v.is_array_of_tables() && !v.as_array()->empty()) {
            tables.push_back(key);
            continue;
        }
        write_pair(out, key, v);
    }
    for (const auto& key : tables)
        for (const toml::node& item : *t.get(key)->as_array()) {
            out << "\n[[" << toml_key(name) << "." << toml_key(key) << "]]\n";
            for (const auto& [k, v] : *item.as_table()) write_pair(out, std::string(k.str()), v);
        }
}

}  // namespace

std::string toml_key(const std::string& key) {
    const bool bare = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    });
    if (bare) return key;
    std::ostringstream quoted;  // a quoted key is a basic string
    quoted << toml::toml_formatter{toml::value<std::string>(key), toml::format_flags::allow_unicode_strings};
    return quoted.str();
}

void write_toml(std::ostream& out, const toml::table& root, const std::vector<std::string>& top,
                const std::vector<SectionOrder>& sections) {
    std::vector<std::string> written;
    for (const auto& key : ordered(root, top)) {
        const toml::node& v = *root.get(key);
        if (v.is_table()) continue;
        write_pair(out, key, v);
    }
    for (const SectionOrder& s : sections) {
        if (const toml::table* t = root[s.section].as_table()) write_section(out, s.section, *t, s.first);
        written.push_back(s.section);
    }
    // Any other table: after those named.
    for (const auto& [key, v] : root)
        if (const toml::table* t = v.as_table();
            t && std::find(written.begin(), written.end(), std::string(key.str())) == written.end())
            write_section(out, std::string(key.str()), *t, {});
}

}  // namespace description
