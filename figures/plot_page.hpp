#pragma once
// Pages of plots: plot panels side by side, and the colours and line widths
// a description's [style] gives them.

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "figures/settings.hpp"
#include "render/canvas.hpp"
#include "render/image.hpp"
#include "render/plot.hpp"

namespace figures {

// A row of plots on a white width x height page (pixels, already scaled).
render::Image draw_plot_row(const std::vector<render::Axes>& axes, int width, int height, double scale);

// The same into `area` of a canvas being drawn.
void draw_plot_row(const render::Canvas& canvas, const render::Rect& area, const std::vector<render::Axes>& axes,
                   double scale);

// A colour from [style] ("#rrggbb" or a name), opaque.
glm::vec4 style_colour(Settings& style, const std::string& key, const std::string& fallback);

// Series shorthands in the book's terms.
render::Series line_series(std::vector<double> x, std::vector<double> y, std::string label, glm::vec4 colour,
                           float width, bool dashed);
render::Series dot_series(std::vector<double> x, std::vector<double> y, std::string label, glm::vec4 colour,
                          float size);

}  // namespace figures
