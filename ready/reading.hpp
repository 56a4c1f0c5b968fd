#pragma once
// The parts of a Ready pattern file, each read by functions of its own
// (ready/pattern.cpp puts them together): values of the XML, the start's
// overlays, Ready's render settings and the stored arrays. What a part
// finds wrong is a Refused, said in words that name the file's elements
// and quote none of its text but a short name, escaped. Not for use
// outside ready/.

#include <tinyxml2.h>
#include <toml++/toml.h>

#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "description/stored_start.hpp"
#include "ready/vtk_arrays.hpp"

namespace ready::reading {

using tinyxml2::XMLElement;

// What goes wrong in a file, before the file's name is put in front.
struct Refused : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// --- values (ready/xml_values.cpp) ---
std::string trimmed(const char* text);
// The lines after the first without the indentation they share (the XML's).
std::string dedented(const std::string& text);
// "<formula number_of_chemicals>": an element, and its attribute, as messages name them.
std::string element(const XMLElement* e, const char* attribute = nullptr);
// A finite number; `what` names it in the refusal.
double number(const char* text, const std::string& what);
double attribute(const XMLElement* e, const char* name, std::optional<double> fallback = std::nullopt);
// An integer attribute from `low` to `high`, refused as written otherwise.
long long integer(const XMLElement* e, const char* name, long long fallback, long long low, long long high);
std::string text_attribute(const XMLElement* e, const char* name, const std::string& fallback);
// The value as the shortest decimal of the float Ready holds (past float's range: as given).
double as_float(double v);
// Text a description may hold: as given when it is text, else escaped.
std::string as_text(const std::string& s, std::size_t most);
const XMLElement* child(const XMLElement* e, const char* name);
const XMLElement* required(const XMLElement* e, const char* name);
bool is_chemical(const std::string& name, int chemicals);

// The grid: <ImageData WholeExtent>, in 1, 2 or 3 dimensions.
struct Grid {
    long long width = 0, height = 0, depth = 1;
};

// --- the start's overlays (ready/overlays.cpp) ---
// One <overlay> as a table of params.initial, or nothing when it can never
// apply; the parameters its fills name are added to `parameters_used`.
std::optional<toml::table> overlay(const XMLElement* o, int chemicals, std::set<std::string>& parameters_used);

// --- Ready's render settings (ready/render_settings.cpp) ---
// [style] from <render_settings>: the active chemical through Ready's colour map from low to high.
toml::table style_of(const XMLElement* rs, int chemicals);

// --- the stored arrays (ready/stored_arrays.cpp) ---
// The stored arrays: a, b, ... in PointData, as Ready names them; or, as
// its older files have it, one array of a component per chemical.
struct StoredArrays {
    std::vector<const XMLElement*> named;  // a, b, ... in order
    const XMLElement* components = nullptr;
    bool float64 = false;
    bool found() const { return !named.empty() || components; }
};

StoredArrays stored_arrays(const XMLElement* piece, int chemicals);
// "it starts from its stored arrays, but holds neither ...".
std::string no_arrays(int chemicals);
// The arrays' shape alone: nothing decoded.
std::shared_ptr<description::StoredStart> start_shape(const StoredArrays& stored, const Grid& grid, int chemicals);
// The arrays decoded (at most max_start_bytes of them, as doubles).
std::shared_ptr<description::StoredStart> decode_start(const StoredArrays& stored, const XMLElement* vtk,
                                                       const std::string& raw, vtk::Encoding enc, const Grid& grid,
                                                       int chemicals);

}  // namespace ready::reading
