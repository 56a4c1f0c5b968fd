#include "render/layout.hpp"

#include <algorithm>
#include <cstdio>
#include <span>

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
    GridText layout{std::move(panels), {}, {}};
    const Font& font = font_of_size(font_pixels);
    for (std::size_t i = 0; i < layout.panels.size(); ++i) {
        const Rect& p = layout.panels[i];
        if (i >= titles.size() || titles[i].empty()) {
            layout.titles.push_back({p.centre().x, p.y, 0, 0});
            layout.inks.push_back({layout.titles.back(), {}});
            continue;
        }
        const float w = font.width(titles[i]), h = font.ascender() - font.descender();
        const float top = place == TitlePlace::above ? p.y - pad - font.ascender() : p.bottom() + pad;
        layout.titles.push_back({p.centre().x - w / 2, top, w, h});
        // As draw_panel_decorations and the snowflakes' captions draw them.
        layout.inks.push_back(place == TitlePlace::above
                                  ? line_ink(font, titles[i], {p.centre().x, p.y - pad}, Align::centre)
                                  : line_ink(font, titles[i], {p.centre().x, top}, Align::centre, Baseline::top));
    }
    return layout;
}

namespace {

std::string box_text(const Rect& r) {
    char text[96];
    std::snprintf(text, sizeof text, "[%.0f, %.0f, %.0f x %.0f]", r.x, r.y, r.w, r.h);
    return text;
}

}  // namespace

void PageText::add(const PageText& other) {
    const int offset = static_cast<int>(panels.size());
    panels.insert(panels.end(), other.panels.begin(), other.panels.end());
    for (Box text : other.texts) {
        if (text.within >= 0) text.within += offset;
        texts.push_back(std::move(text));
    }
}

PageText page_text(const GridText& grid) {
    PageText page;
    for (std::size_t i = 0; i < grid.panels.size(); ++i)
        page.panels.push_back({grid.panels[i], "panel " + std::to_string(i + 1)});
    for (std::size_t i = 0; i < grid.titles.size(); ++i) {
        const std::string what = "the title of panel " + std::to_string(i + 1);
        if (i < grid.inks.size()) page.texts.push_back({grid.inks[i].box, what, -1, grid.inks[i].glyphs, grid.inks[i].em});
        else page.texts.push_back({grid.titles[i], what});
    }
    return page;
}

std::string text_clash(const PageText& layout, const Rect& page) {
    const float slack = 0.5f;  // rounding of pixel positions
    auto inside = [slack](const Rect& r, const Rect& room) {
        return r.x >= room.x - slack && r.y >= room.y - slack && r.right() <= room.right() + slack &&
               r.bottom() <= room.bottom() + slack;
    };
    // Overlapping by more than the slack both ways.
    auto clash = [slack](const Rect& a, const Rect& b) {
        return a.w > 0 && b.w > 0 && a.x + slack < b.right() && b.x + slack < a.right() && a.y + slack < b.bottom() &&
               b.y + slack < a.bottom();
    };
    // A text's glyphs, or its box when it has none listed.
    auto parts = [](const PageText::Box& t) { return t.parts.empty() ? std::span<const Rect>(&t.box, 1) : std::span<const Rect>(t.parts); };
    auto grown = [](const Rect& r, float by) { return Rect{r.x - by, r.y - by, r.w + 2 * by, r.h + 2 * by}; };
    // Each glyph of one against the other's glyphs within reach along x
    // (sorted by their left edges, the widest bounding how far left one may
    // start): two long lines cost O(n log n), not every pair of glyphs.
    auto texts_clash = [&](const PageText::Box& a, const PageText::Box& b, float gap) {
        if (!clash(grown(a.box, gap), b.box)) return false;
        std::vector<Rect> others;
        float widest = 0;
        for (const Rect& q : parts(b))
            if (clash(grown(a.box, gap), q)) {
                others.push_back(q);
                widest = std::max(widest, q.w);
            }
        std::sort(others.begin(), others.end(), [](const Rect& l, const Rect& r) { return l.x < r.x; });
        for (const Rect& p : parts(a)) {
            const Rect g = grown(p, gap);
            auto q = std::lower_bound(others.begin(), others.end(), g.x - widest,
                                      [](const Rect& r, float x) { return r.x < x; });
            for (; q != others.end() && q->x < g.right(); ++q)
                if (clash(g, *q)) return true;
        }
        return false;
    };
    auto clashes_panel = [&](const PageText::Box& t, const Rect& panel) {
        if (!clash(t.box, panel)) return false;
        for (const Rect& p : parts(t))
            if (clash(p, panel)) return true;
        return false;
    };
    // First what leaves its room, the cause of most overlaps, then the overlaps.
    for (const PageText::Box& t : layout.texts) {
        if (t.box.w <= 0) continue;
        const std::string which = t.what + " " + box_text(t.box);
        if (!inside(t.box, page)) return which + " runs off the page";
        if (t.within >= 0 && static_cast<std::size_t>(t.within) < layout.panels.size() &&
            !inside(t.box, layout.panels[static_cast<std::size_t>(t.within)].box))
            return which + " runs out of " + layout.panels[static_cast<std::size_t>(t.within)].what;
    }
    for (std::size_t i = 0; i < layout.texts.size(); ++i) {
        const PageText::Box& t = layout.texts[i];
        if (t.box.w <= 0) continue;
        const std::string which = t.what + " " + box_text(t.box);
        for (std::size_t j = 0; j < layout.texts.size(); ++j)
            if (j != i && texts_clash(t, layout.texts[j], text_gap * std::max(t.em, layout.texts[j].em)))
                return which + (texts_clash(t, layout.texts[j], 0) ? " overlaps " : " is closer than a quarter em to ") +
                       layout.texts[j].what;
        if (t.within < 0)
            for (const PageText::Box& panel : layout.panels)
                if (clashes_panel(t, panel.box)) return which + " overlaps " + panel.what;
    }
    return "";
}

std::string text_clash(const GridText& layout, const Rect& page) { return text_clash(page_text(layout), page); }

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
