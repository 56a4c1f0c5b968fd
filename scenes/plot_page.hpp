#pragma once
// Pages of plots: plot panels side by side, and the colours and line widths
// a description's [style] gives them.

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "scenes/description_names.hpp"
#include "description/settings.hpp"
#include "render/gl/canvas.hpp"
#include "render/image.hpp"
#include "scenes/output.hpp"
#include "scenes/scene.hpp"
#include "render/plot.hpp"

namespace scenes {

// The [style] keys of a plot page (the printed figure's dpi and margins)
// added to a scene's own.
std::vector<Key> with_plot_style_keys(std::vector<Key> keys);

// matplotlib's look at the page's dpi: `plot_scale` (dpi / 100; 1.5 for a
// figure printed at 150 dpi) times the output scale multiplies every font,
// tick and line; `font_size`, `label_size` and `bottom` override the defaults.
render::PlotStyle read_plot_style(Settings& style, double output_scale);

// A row of plots on a white page of the figure's size
// (scenes/figure_caption.hpp): the figure. Throws a SettingError for
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
glm::vec4 style_colour(Settings& style, const std::string& key, const std::string& fallback);

// A list of colours from [style], one per series, used in turn.
std::vector<glm::vec4> style_colours(Settings& style, const std::string& key, const std::vector<std::string>& fallback);

// Series shorthands in the book's terms.
render::Series line_series(std::vector<double> x, std::vector<double> y, std::string label, glm::vec4 colour,
                           float width, bool dashed);
render::Series dot_series(std::vector<double> x, std::vector<double> y, std::string label, glm::vec4 colour,
                          float size);

}  // namespace scenes
