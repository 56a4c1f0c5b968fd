#pragma once
// Two-dimensional plots as matplotlib draws them with its default style:
// linear or log axes with outward ticks and 10^k labels, data lines (solid
// or dashed) and dot markers clipped to the frame, reference lines, notes and
// a legend. Lengths are pixels at scale 1 (matplotlib's points at 72 dpi
// times 100/72: a figure saved at 100 dpi); PlotStyle::scale multiplies them.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "render/surface.hpp"
#include "render/colormap.hpp"
#include "render/layout.hpp"
#include "render/text.hpp"
#include "render/ticks.hpp"

namespace render {

enum class Scale { linear, log };
enum class Legend { none, upper_left, upper_right, lower_left, lower_right };
enum class Direction { horizontal, vertical };

struct Series {
    std::vector<double> x, y;          // data; a pair with a non-finite value, or a non-positive one on a log axis, is
                                       // skipped and breaks the line there (matplotlib's masked points)
    std::string label;                 // legend entry; empty: not in the legend
    glm::vec4 colour{0.12f, 0.47f, 0.71f, 1.0f};  // matplotlib's C0; alpha < 1 keeps one shade where the line crosses itself
    float line_width = 1.5f;           // pixels at scale 1; 0: no line
    std::vector<float> dash;           // on/off lengths in pixels at scale 1; empty: solid (see dashed())
    float marker_size = 0.0f;          // diameter of a dot marker in pixels at scale 1, without its rim; 0: none
};

// matplotlib's "--" pattern for a line `line_width` wide: 3.7 on, 1.6 off, in widths.
inline std::vector<float> dashed(float line_width) { return {3.7f * line_width, 1.6f * line_width}; }

// A line across the whole frame at one data value: matplotlib's axhline/axvline.
struct ReferenceLine {
    Direction direction = Direction::horizontal;
    double at = 0;                     // y of a horizontal line, x of a vertical one, data units
    glm::vec4 colour{0, 0, 0, 1};
    float line_width = 1.0f;           // pixels at scale 1
    std::vector<float> dash;           // as Series::dash
};

// Text placed in axes fraction: ax.text(x, y, s, transform=ax.transAxes).
struct Note {
    std::string text;
    glm::vec2 at;                      // axes fraction: (0,0) bottom-left, (1,1) top-right; the baseline's anchor
    Align align = Align::left;
    glm::vec4 colour{0, 0, 0, 1};
};

struct Axes {
    Scale x_scale = Scale::linear, y_scale = Scale::linear;
    std::optional<std::pair<double, double>> x_range, y_range;  // automatic when absent: the data (and reference lines) plus 5% margins
    std::string x_label, y_label, title;
    Legend legend = Legend::none;
    std::vector<Series> series;        // drawn in order; legend lists them in order
    std::vector<ReferenceLine> reference_lines;  // drawn under the series
    std::vector<Note> notes;
    bool y_down = false;               // matplotlib's invert_yaxis: the y range's low end at the top (time down)
};

struct PlotStyle {
    float scale = 1;                // multiplies every length below and the series' widths and sizes
    float font_size = 14;           // tick labels and notes: matplotlib's 10 pt at 100 dpi
    float label_size = 14;          // axis labels and legend entries
    float title_size = 16;          // 12 pt
    float legend_em = 0;            // unit of the legend's paddings and sample length; 0: label_size
    float spine_width = 1.1f;       // 0.8 pt
    float major_tick = 4.9f;        // length, outwards: 3.5 pt
    float minor_tick = 2.8f;        // 2 pt
    float major_tick_width = 1.1f;  // 0.8 pt
    float minor_tick_width = 0.8f;  // 0.6 pt
    float tick_pad = 4.9f;          // tick end to its label: 3.5 pt
    float label_pad = 5.6f;         // tick labels to the axis label: 4 pt
    float title_pad = 8.3f;         // frame top to the title's baseline: 6 pt
    float marker_edge = 1.4f;       // width of a marker's rim, in its colour (1 pt): translucent markers show it darker
    glm::vec4 ink{0, 0, 0, 1};      // spines, ticks and text
    // plot_row's page margins as fractions of the page (matplotlib's figure.subplot.*)
    float left = 0.125f, right = 0.9f, bottom = 0.11f, top = 0.88f;  // frame edges, from the left and from the bottom
    float wspace = 0.2f;            // gap between frames, in frame widths
};

// Draws axes into `frame` (the plotting area's rectangle: spines lie on its
// edges; tick labels and axis labels go outside it, so the caller leaves
// room). Throws std::invalid_argument for a given range that is not finite,
// or not positive on a log axis.
void draw_axes(Surface& surface, const Rect& frame, const Axes& axes, const PlotStyle& style);

// The text draw_axes would draw around `frame`, as boxes on `page` for its
// fit check (render/layout.hpp's text_clash): the tick labels, axis labels
// and title, which must keep clear of every frame, and the notes and the
// legend, which must stay inside their own. The frame becomes one of the
// page's panels. Names end " of plot N" when `plot` > 0.
void axes_text(PageText& page, const Rect& frame, const Axes& axes, const PlotStyle& style, int plot);

// A colour bar beside a field, as matplotlib's colorbar draws one: the
// colormap's entries as a column, the first at the bottom, in a thin frame,
// with outward ticks and their labels on its right and its label turned
// along it, beyond them.
struct ColourBar {
    Colormap colormap;       // the entries shown, bottom to top, each an equal share of the bar
    double low = 0, high = 1;  // the values at the bar's bottom and top edges (low < high)
    std::string label;       // empty: none
};

// matplotlib's default proportions: the bar is 1/20 of its height wide
// (aspect 20) and stands 0.05 of the field's width (pad) to its right.
inline constexpr float colour_bar_aspect = 20;
inline constexpr float colour_bar_pad = 0.05f;

// The width a colour bar `height` pixels tall takes beside its field of
// width `field_width`: the pad, the bar, its ticks, their widest label and
// its own label, at style's sizes.
float colour_bar_room(const ColourBar& bar, float field_width, float height, const PlotStyle& style);

// The ticks a colour bar `height` pixels tall shows: linear ticks within
// low..high, as many as fit (matplotlib's colorbar locator).
std::vector<Tick> colour_bar_ticks(const ColourBar& bar, float height, const PlotStyle& style);

// Draws it beside `field` (its rectangle): the bar as tall as the field.
// Throws std::invalid_argument unless low < high, both finite, and the
// colormap has entries.
void draw_colour_bar(Surface& surface, const Rect& field, const ColourBar& bar, const PlotStyle& style);

// The text draw_colour_bar would draw beside `field`, as boxes on `page`,
// the bar itself one of its panels; named " of panel N" when `panel` > 0.
void colour_bar_text(PageText& page, const Rect& field, const ColourBar& bar, const PlotStyle& style, int panel);

// Frames for `count` plots side by side on a width x height page, like
// matplotlib's subplots(1, count) with its default margins (style's left
// 0.125, right 0.9, bottom 0.11, top 0.88, wspace 0.2), widened where the
// page is too small to hold the tick labels, axis labels and title at style's
// sizes. Whole pixels. `min_left` and `min_gap` (pixels) widen the left
// margin and the gaps between frames to at least that: the room a plot's
// measured y tick labels and y label need (plot_page's plot_frames).
std::vector<Rect> plot_row(int width, int height, int count, const PlotStyle& style, float min_left = 0,
                           float min_gap = 0);

}  // namespace render
