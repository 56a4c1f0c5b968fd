#pragma once
// Figure layout: a row of equal panels on a white page, each in a thin frame
// with its title above, like matplotlib's subplots(1, n) with imshow.

#include <string>
#include <vector>

#include "render/canvas.hpp"

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

// The frames and titles of the panels, drawn over their contents.
void draw_panel_decorations(Surface& surface, const std::vector<Rect>& panels,
                            const std::vector<std::string>& titles, const PanelRowStyle& style);

}  // namespace render
