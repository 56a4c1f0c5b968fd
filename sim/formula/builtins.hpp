#pragma once
// The built-in functions a formula may call: an allow-list of OpenCL's math
// built-ins, each with its number of arguments and its operation.

#include <string>

#include "sim/formula/program.hpp"

namespace sim::formula {

struct Builtin {
    const char* name;
    int arity;
    Fn fn;
};

// The built-in function called `name`, or nullptr.
const Builtin* find_builtin(const std::string& name);

}  // namespace sim::formula
