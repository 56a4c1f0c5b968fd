// The values of a pattern's XML: numbers, integers and text, checked and shown as given.
#include "ready/reading.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include "description/integer_text.hpp"
#include "description/plain_name.hpp"

namespace ready::reading {

using description::printable_short;

std::string trimmed(const char* text) {
    std::string s = text ? text : "";
    const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
    s.erase(s.begin(), std::find_if_not(s.begin(), s.end(), space));
    s.erase(std::find_if_not(s.rbegin(), s.rend(), space).base(), s.end());
    return s;
}

// The lines after the first without the indentation they share (the XML's).
std::string dedented(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    std::size_t common = std::string::npos;
    for (std::size_t i = 1; i < lines.size(); ++i) {
        const std::size_t indent = lines[i].find_first_not_of(" \t");
        if (indent != std::string::npos) common = std::min(common, indent);
    }
    std::string out;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const bool cut = i > 0 && common != std::string::npos && lines[i].size() >= common;
        if (i > 0) out += '\n';
        out.append(lines[i], cut ? common : 0, std::string::npos);
    }
    return out;
}

// "<formula number_of_chemicals>", "<param name=\"k\">": an element, and
// its attribute, as messages name them.
std::string element(const XMLElement* e, const char* attribute) {
    // Appended piece by piece: GCC 12's -Wrestrict misfires on "<" + string.
    std::string text(1, '<');
    text += printable_short(e->Name(), 40);
    if (attribute) {
        text += ' ';
        text += attribute;
    }
    text += '>';
    return text;
}

double number(const char* text, const std::string& what) {
    const std::string s = trimmed(text);
    double v = 0;
    const char* from = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
    const auto [end, ec] = std::from_chars(from, s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
        throw Refused(what + " is \"" + printable_short(s) + "\", not a finite number");
    return v;
}

double attribute(const XMLElement* e, const char* name, std::optional<double> fallback) {
    const char* text = e->Attribute(name);
    if (!text) {
        if (fallback) return *fallback;
        throw Refused(element(e) + " has no " + name);
    }
    return number(text, element(e, name));
}

// An integer attribute from `low` to `high`, refused as written otherwise.
long long integer(const XMLElement* e, const char* name, long long fallback, long long low, long long high) {
    const char* text = e->Attribute(name);
    if (!text) return fallback;
    const std::string s = trimmed(text);
    if (const auto v = description::integer_text(s, low, high)) return *v;
    throw Refused(element(e, name) + " is \"" + printable_short(s) + "\", not an integer from " + std::to_string(low) +
                  " to " + std::to_string(high));
}

std::string text_attribute(const XMLElement* e, const char* name, const std::string& fallback) {
    const char* text = e->Attribute(name);
    return text ? trimmed(text) : fallback;
}

// Ready holds its parameters and overlay numbers as float: the value as
// the shortest decimal of that float. A value past float's range is kept
// as given, for the scene to refuse as it was written.
double as_float(double v) {
    if (std::fabs(v) > std::numeric_limits<float>::max()) return v;
    const float f = static_cast<float>(v);
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, f);
    double out = 0;
    std::from_chars(text, end, out);
    return out;
}

// Text a description may hold: as given when it is text, else escaped.
std::string as_text(const std::string& s, std::size_t most) {
    return description::is_text(s) && s.size() <= most ? s : printable_short(s, most);
}

const XMLElement* child(const XMLElement* e, const char* name) { return e ? e->FirstChildElement(name) : nullptr; }

const XMLElement* required(const XMLElement* e, const char* name) {
    const XMLElement* c = child(e, name);
    if (!c) throw Refused("no <" + std::string(name) + "> in " + element(e));
    return c;
}

bool is_chemical(const std::string& name, int chemicals) {
    return name.size() == 1 && name[0] >= 'a' && name[0] < 'a' + chemicals;
}

}  // namespace ready::reading
