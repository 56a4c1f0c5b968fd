#pragma once
// Figure layout: a row of equal panels on a white page, each in a thin frame
// with its title above, like matplotlib's subplots(1, n) with imshow.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "render/surface.hpp"
#include "render/text.hpp"

namespace render {

struct PanelRowStyle {
    float scale = 1.0f;        // multiplies every length below
    float margin = 12.0f;      // page edge to the nearest panel or title, pixels
    float gap = 28.0f;         // between neighbouring panels
    float title_size = 17.0f;  // title font size (12 pt at 100 dpi, matplotlib's default title)
    float title_pad = 6.0f;    // title baseline above the panel's top edge
    float frame_width = 1.0f;  // the panel's outline (matplotlib's 0.8 pt spine)
    float aspect = 1.0f;       // panel width / height
};

// Where each of `count` panels goes in `area`: as large as fits, centred,
// with room above for titles when `titled`.
std::vector<Rect> panel_row(const Rect& area, int count, bool titled, const PanelRowStyle& style);
// The same on a whole width x height page.
std::vector<Rect> panel_row(int width, int height, int count, bool titled, const PanelRowStyle& style);
// `count` panels in rows of `columns`, the area split into equal bands.
std::vector<Rect> panel_grid(const Rect& area, int count, int columns, bool titled, const PanelRowStyle& style);

// The columns that give `count` panels of style.aspect the largest size in
// `area` (panel_grid's layout), weighed by the square of the share of the
// grid's cells they fill, so that a ragged last row must buy much larger
// panels; of equal scores, the fewest columns. Four square panels on a
// square page: 2 x 2, never 3 + 1.
int best_columns(const Rect& area, int count, bool titled, const PanelRowStyle& style);

// Where a grid's text goes, to check that it fits.
enum class TitlePlace { above, below };  // a title over its panel, or a caption under it
struct GridText {
    std::vector<Rect> panels;
    std::vector<Rect> titles;  // each title's line box (advance width x ascender to descender), where it is
                               // drawn; w = 0: none
    std::vector<LineInk> inks;  // each title's ink (render::line_ink), what the fit check reads
};
// The boxes of `titles` (one a panel, centred on it) at `place`, in `font_pixels`.
// Above: the baseline `pad` over the panel's top; below: the line box's top
// `pad` under its bottom.
GridText grid_text(std::vector<Rect> panels, const std::vector<std::string>& titles, TitlePlace place,
                   float font_pixels, float pad);
// Any page's text, to check that it fits: the boxes of its lines, each
// named for the message that says what clashes, and the panels (plot frames,
// fields, colour bars) they must keep clear of or stay inside.
struct PageText {
    struct Box {
        Rect box;
        std::string what;  // "the title of panel 2", "the x tick label "0.5" of plot 1"
        int within = -1;   // the panel a text belongs inside (a legend, a note), -1: outside every panel
        std::vector<Rect> parts = {};  // a text's glyphs, all inside `box`; empty: the box is solid
        float em = 0;             // a text's font size, pixels: it keeps text_gap of them from other texts
    };
    std::vector<Box> panels;
    std::vector<Box> texts;  // w = 0: none, never clashes
    // Adds `other`'s panels and texts, its `within` indices moved past this one's panels.
    void add(const PageText& other);
};
// A grid's titles as page text: "the title of panel N" over "panel N".
PageText page_text(const GridText& grid);

// The room two texts keep between their glyphs, in ems of the larger font:
// a quarter, a little less than DejaVu Sans's space (0.32 em), so that two
// titles side by side read as two, not as one ("step 1000step 3000").
inline constexpr float text_gap = 0.25f;

// What is wrong with the text of `layout` on `page`: a text that leaves the
// page, comes within text_gap of another text, overlaps a panel, or (one
// that belongs inside a panel) leaves its panel. Texts are where their
// glyphs' ink boxes are (parts). Empty when it all fits. Half a pixel of
// overlap is rounding.
std::string text_clash(const PageText& layout, const Rect& page);
std::string text_clash(const GridText& layout, const Rect& page);
// The smallest page, `width` x `height` enlarged by steps of 5% (its aspect
// kept, up to 8 times, neither side beyond `most`), at which
// `layout_at(w, h)` has no clash; {0, 0} when none up to that.
struct PageSize {
    int width = 0, height = 0;
};
template <class LayoutAt>
PageSize size_that_fits(int width, int height, LayoutAt&& layout_at, int most = std::numeric_limits<int>::max()) {
    for (int step = 1; step <= 43; ++step) {  // 1.05^43 ~ 8
        const double k = std::pow(1.05, step);
        const double w = std::ceil(width * k), h = std::ceil(height * k);
        if (w > most || h > most) break;
        if (text_clash(layout_at(int(w), int(h)), Rect{0, 0, float(w), float(h)}).empty()) return {int(w), int(h)};
    }
    return {};
}

// The frames and titles of the panels, drawn over their contents.
void draw_panel_decorations(Surface& surface, const std::vector<Rect>& panels,
                            const std::vector<std::string>& titles, const PanelRowStyle& style);

}  // namespace render
