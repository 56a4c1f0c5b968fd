#include "render/layout.hpp"

#include <algorithm>
#include <cstdio>

#include "render/shapes.hpp"
#include "render/text.hpp"

namespace render {

std::vector<Rect> panel_row(const Rect& area, int count, bool titled, const PanelRowStyle& style) {
    const float s = style.scale;
    const float margin = style.margin * s, gap = style.gap * s;
    const float title_band = titled ? (style.title_size * 1.25f + style.title_pad) * s : 0.0f;
    const float free_w = (area.w - 2 * margin - float(count - 1) * gap) / float(count);
    const float free_h = area.h - 2 * margin - title_band;
    float w = std::max(1.0f, free_w), h = w / style.aspect;
    if (h > free_h) {
        h = std::max(1.0f, free_h);
        w = h * style.aspect;
    }
    // Whole pixels: cell edges of nearest-neighbour fields then fall on a
    // stable grid, and the frame lines stay crisp.
    w = std::floor(w);
    h = std::floor(h);
    const float row_w = float(count) * w + float(count - 1) * gap;
    const float x0 = area.x + std::round((area.w - row_w) / 2);
    const float y0 = area.y + std::round((area.h - h - title_band) / 2 + title_band);
    std::vector<Rect> panels;
    for (int i = 0; i < count; ++i) panels.push_back({x0 + float(i) * (w + std::round(gap)), y0, w, h});
    return panels;
}

std::vector<Rect> panel_row(int width, int height, int count, bool titled, const PanelRowStyle& style) {
    return panel_row(Rect{0, 0, float(width), float(height)}, count, titled, style);
}

std::vector<Rect> panel_grid(const Rect& area, int count, int columns, bool titled, const PanelRowStyle& style) {
    const int rows = (count + columns - 1) / columns;
    const float s = style.scale;
    const float title_band = titled ? (style.title_size * 1.25f + style.title_pad) * s : 0.0f;
    // Bands as tall as a panel of the row's width needs (plus its title and
    // a gap), not an equal share of the area: wide panels stay close together.
    const float panel_w = (area.w - 2 * style.margin * s - float(columns - 1) * style.gap * s) / float(columns);
    const float band = std::min(area.h / float(rows), panel_w / style.aspect + title_band + style.gap * s);
    const float top = area.y + std::round((area.h - band * float(rows)) / 2);
    std::vector<Rect> panels;
    for (int r = 0; r < rows; ++r) {
        // Every row is laid out for `columns` panels, so a short last row keeps the same panel size.
        auto row = panel_row(Rect{area.x, top + float(r) * band, area.w, band}, columns, titled, style);
        const int in_row = std::min(columns, count - r * columns);
        panels.insert(panels.end(), row.begin(), row.begin() + in_row);
    }
    return panels;
}

int best_columns(const Rect& area, int count, bool titled, const PanelRowStyle& style) {
    int best = 1;
    float best_score = -1;
    for (int columns = 1; columns <= count; ++columns) {
        const int rows = (count + columns - 1) / columns;
        // A column more that leaves the rows as they are only shrinks the panels.
        if (columns > 1 && rows == (count + columns - 2) / (columns - 1)) continue;
        const Rect r = panel_grid(area, count, columns, titled, style).front();
        // The panels' size, weighed by the square of how full the grid is: a
        // ragged last row must buy much larger panels (three wide panels stay
        // one row on a wide page; four square ones make 2 x 2, never 3 + 1).
        const float full = float(count) / float(rows * columns);
        const float score = r.w * r.h * full * full;
        if (score > best_score * 1.0001f) {
            best_score = score;
            best = columns;
        }
    }
    return best;
}

GridText grid_text(std::vector<Rect> panels, const std::vector<std::string>& titles, TitlePlace place,
                   float font_pixels, float pad) {
    GridText layout{std::move(panels), {}};
    const Font& font = font_of_size(font_pixels);
    for (std::size_t i = 0; i < layout.panels.size(); ++i) {
        const Rect& p = layout.panels[i];
        if (i >= titles.size() || titles[i].empty()) {
            layout.titles.push_back({p.centre().x, p.y, 0, 0});
            continue;
        }
        const float w = font.width(titles[i]), h = font.ascender() - font.descender();
        const float top = place == TitlePlace::above ? p.y - pad - font.ascender() : p.bottom() + pad;
        layout.titles.push_back({p.centre().x - w / 2, top, w, h});
    }
    return layout;
}

namespace {

bool overlap(const Rect& a, const Rect& b) {
    return a.w > 0 && b.w > 0 && a.x < b.right() && b.x < a.right() && a.y < b.bottom() && b.y < a.bottom();
}

std::string box_text(const Rect& r) {
    char text[96];
    std::snprintf(text, sizeof text, "[%.0f, %.0f, %.0f x %.0f]", r.x, r.y, r.w, r.h);
    return text;
}

}  // namespace

std::string text_clash(const GridText& layout, const Rect& page) {
    const float slack = 0.5f;  // rounding of pixel positions
    for (std::size_t i = 0; i < layout.titles.size(); ++i) {
        const Rect& t = layout.titles[i];
        if (t.w <= 0) continue;
        const std::string which = "the title of panel " + std::to_string(i + 1) + " " + box_text(t);
        if (t.x < page.x - slack || t.y < page.y - slack || t.right() > page.right() + slack ||
            t.bottom() > page.bottom() + slack)
            return which + " runs off the page";
        for (std::size_t j = 0; j < layout.titles.size(); ++j)
            if (j != i && overlap(t, layout.titles[j])) return which + " overlaps the title of panel " + std::to_string(j + 1);
        for (std::size_t j = 0; j < layout.panels.size(); ++j)
            if (overlap(t, layout.panels[j])) return which + " overlaps panel " + std::to_string(j + 1);
    }
    return "";
}

void draw_panel_decorations(Surface& surface, const std::vector<Rect>& panels,
                            const std::vector<std::string>& titles, const PanelRowStyle& style) {
    const glm::vec4 black{0, 0, 0, 1};
    Shapes frames;
    for (const Rect& r : panels) frames.frame(r, style.frame_width * style.scale, black);
    frames.draw(surface);
    Text text;
    Font& font = font_of_size(std::round(style.title_size * style.scale));
    for (std::size_t i = 0; i < panels.size() && i < titles.size(); ++i) {
        const Rect& r = panels[i];
        text.add(font, titles[i], {r.x + r.w / 2, r.y - style.title_pad * style.scale}, black, Align::centre,
                 Baseline::baseline);
    }
    text.draw(surface);
}

}  // namespace render
