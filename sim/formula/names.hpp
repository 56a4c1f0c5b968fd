#pragma once
// The names a rule's parameter may not take. A parameter becomes a
// constant of Ready's kernel (`const float NAME = ...;`), declared beside
// the names Ready and OpenCL C already give: one that takes such a name
// would replace a stencil, a neighbour, a position or a constant, or be
// taken for a chemical, and Ready's kernel would not compile. The one
// place descriptions and Ready's files check a parameter's name.

#include <optional>
#include <set>
#include <string>

#include "sim/formula/tree.hpp"

namespace sim::formula {

// Why `name` cannot name a parameter of a rule of `chemicals` chemicals
// (a, b, ...), in any dimension: "a keyword of OpenCL C", "a stencil
// keyword (laplacian of chemical a)", ...; nothing when it can.
std::optional<std::string> parameter_name_clash(const std::string& name, int chemicals);

// The names `formula` reads (variables, parameters, keywords, arrays),
// from its tree: a parameter it never names is one the rule does not use.
std::set<std::string> names_read(const Formula& formula);

// What a parameter's name may be, for messages: "its name is CLASH; " + this.
inline constexpr const char* parameter_name_allowed =
    "a parameter's name is an identifier (a letter or _, then letters, digits and _; at most 64) that is not a "
    "keyword, type, built-in function or constant of OpenCL C, nor a chemical, delta_, neighbour, stencil or "
    "position of the rule";

}  // namespace sim::formula
