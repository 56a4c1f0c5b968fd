#pragma once
// How a scene draws an array, read from [style] as the book's imshow calls
// set it: colormap (or a list of colours), vmin and vmax (absent: each
// panel's own min and max, matplotlib's autoscale), alpha, sampling.

#include <optional>
#include <string>
#include <vector>

#include "description/schema.hpp"
#include "render/colormap.hpp"
#include "scenes/description_names.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "sim/grid.hpp"

namespace scenes {

struct FieldSpec {
    render::Colormap colormap;         // a named map, or colours listed in [style]
    std::optional<double> vmin, vmax;  // absent: autoscale per panel
    float alpha = 0.7f;                // the book's draw_array default
    render::Sampling sampling = render::Sampling::nearest;
    bool colour_bar = false;           // a colour bar beside each panel, with its ticks
    std::string colour_bar_label = {};  // and this label beside it
};

// The [style] keys of a FieldSpec; a scene with several fields gives each
// its prefix (Schema::part: "b_" gives b_colormap).
const description::Schema<FieldSpec>& field_spec_schema();

// Whether a layer copies its grid's cells (a panel kept while the model runs
// on) or looks at them where they are (a frame drawn at once, the grid
// unchanged until it is).
enum class Cells { copied, viewed };

// One layer of a panel: the values as doubles with the spec's colour range.
FieldLayer field_layer(const sim::Grid<double>& values, const FieldSpec& spec, Cells cells = Cells::copied);
FieldLayer field_layer(const sim::Grid<std::uint8_t>& values, const FieldSpec& spec);

}  // namespace scenes
