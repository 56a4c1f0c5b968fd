#pragma once
// A description as TOML text a person reads: the top-level keys first, then
// [params], [style], [figure] and [animation], each with the keys it names
// first in that order. Every key and string goes through toml++'s
// formatter, quoted and escaped as TOML needs, so any name and any text
// (a formula holding ''' or """, a name holding a line break) reads back
// as the same table; numbers are the shortest text that reads back the same.

#include <toml++/toml.h>

#include <ostream>
#include <string>
#include <vector>

namespace description {

// The order a section's keys are written in: `first`, then the others.
struct SectionOrder {
    std::string section;
    std::vector<std::string> first;
};

// Writes `root`: its top-level keys in the order `top` names first, then
// each of `sections` that it holds, each with its arrays of tables last
// (as [[section.key]]).
void write_toml(std::ostream& out, const toml::table& root, const std::vector<std::string>& top,
                const std::vector<SectionOrder>& sections);

// `key` as TOML writes it: bare when it may be, else a quoted string.
std::string toml_key(const std::string& key);

}  // namespace description
