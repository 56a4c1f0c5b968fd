#pragma once
// Pages of plots: plot panels side by side, and the colours and line widths
// a description's [style] gives them.

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "description/schema.hpp"
#include "render/image.hpp"
#include "render/plot.hpp"
#include "scenes/description_names.hpp"
#include "scenes/output.hpp"
#include "scenes/scene.hpp"

namespace scenes {

// A plot page's [style] keys, as read: the printed figure's dpi and margins.
struct PlotSettings {
    double plot_scale = 1.0;  // dpi / 100: 1.5 for a figure printed at 150 dpi
    render::PlotStyle plot;   // font_size, label_size and bottom as given
};
// Their schema, for a scene's style schema to take as a part.
const description::Schema<PlotSettings>& plot_settings_schema();

// matplotlib's look at the page's dpi: plot_scale times the output scale
// multiplies every font, tick and line.
render::PlotStyle plot_style(const PlotSettings& settings, double output_scale);

// A row of plots on a white page of the figure's size
// (scenes/helpers/figure_caption.hpp): the figure. Throws a SettingError for
// figure.size, with a size that holds it, when their text does not fit:
// tick labels, axis labels and titles that overlap each other or a frame or
// leave the page, legends and notes that leave their frames.
FigureDrawing plot_figure(std::vector<render::Axes> axes, const Description& d, const SceneOptions& options,
                          const render::PlotStyle& style);

// The same into `area` of a surface being drawn.
void draw_plot_row(render::Surface& surface, const render::Rect& area, const std::vector<render::Axes>& axes,
                   const render::PlotStyle& style);

// The text draw_plot_row would draw, for render::text_clash: each plot's
// frame and the boxes of its text (render::axes_text).
render::PageText plot_row_text(const render::Rect& area, const std::vector<render::Axes>& axes,
                               const render::PlotStyle& style);

// A colour from [style] ("#rrggbb" or a name), opaque.
// A colour of [style]: as written, and what it names.
struct Colour {
    std::string name;  // "#526e97", "orange"
    glm::vec4 rgba;
};
// A known colour, for a scene's defaults (std::logic_error for a name that is not).
Colour colour(const std::string& name);
void to_json(nlohmann::json& json, const Colour& colour);  // the metadata keeps the name

// Schema::field readers: a colour, and a list of them, one per series, used in turn.
Colour read_colour(Settings& style, const std::string& key, const Colour& fallback);
std::vector<Colour> read_colours(Settings& style, const std::string& key, const std::vector<Colour>& fallback);

// Series shorthands in the book's terms.
render::Series line_series(std::vector<double> x, std::vector<double> y, std::string label, glm::vec4 colour,
                           float width, bool dashed);
render::Series dot_series(std::vector<double> x, std::vector<double> y, std::string label, glm::vec4 colour,
                          float size);

}  // namespace scenes
