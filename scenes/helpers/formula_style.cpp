// How a formula model's chemicals are drawn: scenes/helpers/formula_style.hpp.

#include "scenes/helpers/formula_style.hpp"

#include <algorithm>

#include "scenes/helpers/formula_model.hpp"
#include "sim/formula/rule.hpp"

namespace formula = sim::formula;

namespace scenes {

using description::Schema;
using description::Settings;

// How chemical c is drawn unless [style] says otherwise: one chemical shown
// through viridis, or several stacked in Reds, Blues, Greens, Purples.
namespace {

FieldSpec default_spec(const std::vector<int>& shown, int c) {
    static const char* stacked[] = {"Reds", "Blues", "Greens", "Purples"};
    const auto at = std::find(shown.begin(), shown.end(), c);
    const std::size_t place = at == shown.end() ? 0 : static_cast<std::size_t>(at - shown.begin());
    return shown.size() == 1 ? FieldSpec{render::colormap("viridis"), {}, {}, 1.0f, render::Sampling::smooth}
                             : FieldSpec{render::colormap(stacked[place]), {}, {}, 0.7f, render::Sampling::smooth};
}


}  // namespace

FormulaStyle formula_style_defaults(int chemicals) {
    FormulaStyle s;
    for (int c = 0; c < chemicals; ++c) s.chemicals.push_back(default_spec(s.shown, c));
    return s;
}

// The rule's chemicals as the description gives them: a drawing for each.
Schema<FormulaStyle> formula_style_schema(int chemicals) {
    Schema<FormulaStyle> s;
    s.key(
        {"show", "the chemicals each panel shows, stacked in this order, e.g. [\"a\", \"b\"]", "a list of strings",
         "one to four chemicals of the rule"},
        [chemicals](Settings& style, const std::string& key, FormulaStyle& v) {
            v.show = style.texts(key, v.show);
            v.shown.clear();
            for (const std::string& name : v.show) v.shown.push_back(chemical_index(style, key, name, chemicals, true));
            if (v.shown.empty() || v.shown.size() > 4) style.refuse(key, "one to four chemicals, e.g. [\"a\"]");
            // The drawings' defaults follow what is shown.
            for (int c = 0; c < chemicals; ++c) v.chemicals[static_cast<std::size_t>(c)] = default_spec(v.shown, c);
        },
        [](const FormulaStyle& d) { return nlohmann::json(d.show); });
    s.choice("origin", &FormulaStyle::upper, {{"lower", false}, {"upper", true}},
             "where y = 0 is drawn: lower (Ready's, y up) or upper (the book's arrays, row 0 on top)");
    s.number("contour_level", &FormulaStyle::contour_level,
             "a 3-D grid's isosurface: the first chemical shown at this value (Ready's contour_level)", -1e30, 1e30);
    s.choice("contour_inside", &FormulaStyle::contour_below, {{"above", false}, {"below", true}},
             "the region a 3-D grid's isosurface closes (capped on the grid's faces): the values above "
             "contour_level, or below it (Ready's invert_contour_cap)");
    for (int c = 0; c < chemicals; ++c)
        s.part_at(
            field_spec_schema(), [c](auto& v) -> auto& { return v.chemicals[static_cast<std::size_t>(c)]; },
            formula::chemical_name(c) + "_");
    return s;
}

std::vector<FieldSpec> shown_specs(const FormulaStyle& s) {
    std::vector<FieldSpec> specs;
    for (int c : s.shown) specs.push_back(s.chemicals[static_cast<std::size_t>(c)]);
    return specs;
}

}  // namespace scenes
