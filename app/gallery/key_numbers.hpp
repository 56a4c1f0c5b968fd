#pragma once
// The key results of a figure, as its gallery card shows them: a few
// labelled numbers taken from its metadata (slopes, dimensions, p_c,
// exponents, fitted ranges), each beside the catalog's reference value where
// docs/catalog.md (the catalog) gives one. Which numbers a scene's
// metadata holds, and what the catalog says of them, each scene declares
// beside its code (scenes::SceneInfo::key_numbers): data, not code.
//
// The metadata is untrusted (a hand-edited or foreign ID.json): a field that
// is missing or of another type gives no row, never an exception.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace app {

// One row of a card's table.
struct KeyNumberRow {
    std::string label;      // "slope, rule 18"
    std::string value;      // "1.584", "0.59272 ± 0.00003", "4 to 45 cells"
    std::string reference;  // "1.57 (book); log2 3 = 1.585 exactly", or "" for none
    std::string path;       // the JSON pointer of the value in the metadata, "/panels/2/slope"
    std::string error_path; // the pointer of its standard error ("± ..."), or ""
    std::string kind;       // how `value` reads it: "number", "integer", "range" (first to last of a
                            // list), "bounds" ([xmin, xmax, ymin, ymax]), "count" (a list's length)
};

// The rows for `meta` (a figure's metadata, whose "scene" picks its entries).
std::vector<KeyNumberRow> key_numbers(const nlohmann::json& meta);

// `value` rounded to `digits` significant digits, as the cards show numbers:
// 0.592746 -> "0.5927", 2.000191 -> "2.000" (rounded: its zeros kept), 0.02
// -> "0.02" (exact), 12988.27 -> "12988" and 250000 -> "250000" (below 10^9
// in full), 1.5e12 -> "1.500e+12".
std::string significant(double value, int digits);

}  // namespace app
