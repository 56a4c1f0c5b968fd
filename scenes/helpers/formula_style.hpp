#pragma once
// How a formula model's chemicals are drawn ([style]): which are shown, and
// each one's field spec (colormap, range, colour bar) with its chemical's
// prefix (a_colormap, b_vmin, ...). Shared by the formula scene and the
// mesh scene.

#include <string>
#include <vector>

#include "description/schema.hpp"
#include "scenes/helpers/field_spec.hpp"

namespace scenes {

struct FormulaStyle {
    std::vector<std::string> show{"a"};
    std::vector<int> shown{0};
    bool upper = false;
    double contour_level = 0.25;  // a 3-D grid's isosurface: Ready's default level
    bool contour_below = false;   // the isosurface closes the values below the level
    std::vector<FieldSpec> chemicals;  // each chemical's drawing, read and checked; those shown are drawn
};

// One chemical shown through viridis, or several stacked in Reds, Blues, Greens, Purples.
FormulaStyle formula_style_defaults(int chemicals);
description::Schema<FormulaStyle> formula_style_schema(int chemicals);
std::vector<FieldSpec> shown_specs(const FormulaStyle& s);

}  // namespace scenes
