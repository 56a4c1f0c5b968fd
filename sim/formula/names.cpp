#include "sim/formula/names.hpp"

#include <algorithm>
#include <cctype>
#include <set>
#include <vector>

#include "sim/formula/rule.hpp"
#include "sim/formula/stencils.hpp"

namespace sim::formula {
namespace {

bool in(const std::set<std::string>& names, const std::string& name) { return names.count(name) != 0; }

bool starts_with(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

const std::set<std::string> keywords = {
    "if",       "else",     "for",        "while",    "do",        "return",    "break",     "continue",
    "switch",   "case",     "default",    "goto",     "const",     "static",    "extern",    "inline",
    "volatile", "restrict", "register",   "auto",     "struct",    "union",     "enum",      "typedef",
    "sizeof",   "unsigned", "signed",     "void",     "true",      "false",     "kernel",    "__kernel",
    "global",   "__global", "local",      "__local",  "constant",  "__constant", "private",  "__private",
    "read_only", "__read_only", "write_only", "__write_only", "read_write", "__read_write", "__attribute__",
};

bool is_type(const std::string& name) {
    static const std::set<std::string> scalars = {"bool",  "char",   "uchar", "short",  "ushort", "int",
                                                  "uint",  "long",   "ulong", "float",  "double", "half",
                                                  "size_t", "ptrdiff_t", "intptr_t", "uintptr_t", "image2d_t",
                                                  "image3d_t", "sampler_t", "event_t"};
    static const std::set<std::string> vectors = {"char", "uchar", "short", "ushort", "int", "uint",
                                                  "long", "ulong", "float", "double", "half"};
    if (in(scalars, name)) return true;
    for (const char* width : {"2", "3", "4", "8", "16"}) {
        const std::string w = width;
        if (name.size() > w.size() && name.compare(name.size() - w.size(), w.size(), w) == 0 &&
            in(vectors, name.substr(0, name.size() - w.size())))
            return true;
    }
    return false;
}

// OpenCL C's built-in functions of floats beyond the formula language's
// own (which is_builtin_function knows), and the families named by a prefix.
bool is_opencl_function(const std::string& name) {
    // The math of floats, which a formula could mean to call; not the
    // integer and geometric ones (Ready's own patterns name parameters
    // `rotate`, and OpenCL lets a local constant hide such a function).
    static const std::set<std::string> more = {
        "acospi", "asinpi", "atanpi", "atan2pi", "cospi", "sinpi", "tanpi", "erf", "erfc", "fract", "frexp",
        "ilogb", "ldexp", "lgamma", "lgamma_r", "logb", "maxmag", "minmag", "modf", "nan", "nextafter", "pown",
        "remainder", "remquo", "rootn", "sincos", "tgamma", "isnan", "isinf", "isfinite", "isnormal", "isordered",
        "isunordered", "signbit", "isgreater", "isgreaterequal", "isless", "islessequal", "islessgreater",
        "isequal", "isnotequal", "get_global_id", "get_global_size", "get_local_id", "get_local_size", "barrier"};
    if (in(more, name)) return true;
    for (const char* prefix : {"native_", "half_", "convert_", "vload", "vstore", "atomic_", "read_image", "write_image"})
        if (starts_with(name, prefix)) return true;
    return false;
}

bool is_constant(const std::string& name) {
    static const std::set<std::string> constants = {
        "MAXFLOAT", "HUGE_VAL", "HUGE_VALF", "INFINITY", "NAN", "FLT_MAX", "FLT_MIN", "FLT_EPSILON", "FLT_DIG",
        "FLT_MANT_DIG", "FLT_RADIX", "DBL_MAX", "DBL_MIN", "DBL_EPSILON", "DBL_DIG", "DBL_MANT_DIG", "CHAR_BIT",
        "CHAR_MAX", "CHAR_MIN", "INT_MAX", "INT_MIN", "LONG_MAX", "LONG_MIN", "SHRT_MAX", "SHRT_MIN", "UINT_MAX",
        "ULONG_MAX", "UCHAR_MAX", "USHRT_MAX", "SCHAR_MAX", "SCHAR_MIN", "NULL", "CLK_LOCAL_MEM_FENCE",
        "CLK_GLOBAL_MEM_FENCE"};
    return in(constants, name) || starts_with(name, "M_") || starts_with(name, "__") || starts_with(name, "FP_") ||
           starts_with(name, "CL_");
}

// What the kernel Ready writes around a formula declares (its indices,
// sizes, work-group macros).
bool is_kernel_name(const std::string& name) {
    static const std::set<std::string> names = {
        "index_x", "index_y", "index_z", "index_here", "local_x", "local_y", "local_z", "X", "Y", "Z",
        "LX", "LY", "LZ", "XR", "YR", "ZR", "lx", "ly", "lz", "x_start", "x_end", "y_start", "y_end",
        "z_start", "z_end"};
    return in(names, name);
}

// Ready's stencils in 1, 2 and 3 dimensions, at every accuracy.
bool is_stencil_label(const std::string& label) {
    static const std::set<std::string> ready = {"laplacian",  "bilaplacian", "trilaplacian",        "x_gradient",
                                                "y_gradient", "z_gradient",  "gradient_mag_squared"};
    if (in(ready, label)) return true;
    const auto& ours = stencil_names();
    return std::find(ours.begin(), ours.end(), label) != ours.end();
}

// Whether `rest` (after "a_") is a direction as Ready names neighbours:
// u/d, then n/s, then e/w, each with an optional count of cells.
bool is_direction(const std::string& rest) {
    std::size_t at = 0;
    bool any = false;
    for (const char* pair : {"ud", "ns", "ew"}) {
        if (at < rest.size() && (rest[at] == pair[0] || rest[at] == pair[1])) {
            ++at;
            while (at < rest.size() && std::isdigit(static_cast<unsigned char>(rest[at]))) ++at;
            any = true;
        }
    }
    return any && at == rest.size();
}

void read_names(const Expr& e, std::set<std::string>& names) {
    if (e.kind == Expr::Kind::name || e.kind == Expr::Kind::index) names.insert(e.text);
    for (const ExprPtr& a : e.args) read_names(*a, names);
}

void read_names(const Stmt& s, std::set<std::string>& names) {
    for (const Declarator& d : s.declarators)
        if (d.init) read_names(*d.init, names);
    for (const Expr* e : {s.target.get(), s.value.get(), s.condition.get()})
        if (e) read_names(*e, names);
    for (const Stmt* inner : {s.init.get(), s.step.get()})
        if (inner) read_names(*inner, names);
    for (const StmtPtr& b : s.body)
        if (b) read_names(*b, names);
}

}  // namespace

std::set<std::string> names_read(const Formula& formula) {
    std::set<std::string> names;
    for (const StmtPtr& s : formula.statements) read_names(*s, names);
    return names;
}

std::optional<std::string> parameter_name_clash(const std::string& name, int chemicals) {
    const bool identifier =
        !name.empty() && name.size() <= 64 && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
        std::all_of(name.begin(), name.end(), [](char c) {
            return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
        });
    if (!identifier) return "not an identifier";
    if (in(keywords, name)) return "a keyword of OpenCL C";
    if (is_type(name)) return "a type of OpenCL C";
    if (is_builtin_function(name) || is_opencl_function(name)) return "a built-in function";
    if (is_constant(name)) return "a built-in constant";
    if (name == "x_pos" || name == "y_pos" || name == "z_pos") return "a cell's position";
    if (is_kernel_name(name)) return "a name Ready's kernel declares";
    if (name == "dx" || name == "timestep") return std::nullopt;  // parameters Ready itself expects
    const int count = std::clamp(chemicals, 1, max_chemicals);
    for (int i = 0; i < count; ++i) {
        const std::string chem = chemical_name(i);
        if (name == chem) return "chemical " + chem + " of the rule";
        if (name == "delta_" + chem) return "the change of chemical " + chem + " (delta_" + chem + ")";
        if (name == chem + "_in" || name == chem + "_out" || name == "local_" + chem)
            return "a name Ready's kernel declares for chemical " + chem;
        if (name.size() > 2 && name.compare(0, 2, chem + "_") == 0 && is_direction(name.substr(2)))
            return "a neighbour of chemical " + chem;
        const std::string suffix = "_" + chem;
        if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
            is_stencil_label(name.substr(0, name.size() - suffix.size())))
            return "a stencil keyword of chemical " + chem;
    }
    return std::nullopt;
}

}  // namespace sim::formula
