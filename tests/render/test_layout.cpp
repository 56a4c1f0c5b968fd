// Grids of panels and their titles: the columns chosen for the page, and
// text that never overlaps another title, a panel or the page's edge.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "render/layout.hpp"

using render::Rect;

namespace {

// Checked here on the rectangles themselves, not through text_clash.
bool apart(const Rect& a, const Rect& b) {
    return a.right() <= b.x + 0.5f || b.right() <= a.x + 0.5f || a.bottom() <= b.y + 0.5f || b.bottom() <= a.y + 0.5f;
}
bool inside(const Rect& r, const Rect& page) {
    return r.x >= page.x - 0.5f && r.y >= page.y - 0.5f && r.right() <= page.right() + 0.5f &&
           r.bottom() <= page.bottom() + 0.5f;
}

render::GridText layout(const Rect& page, int count, int columns, const render::PanelRowStyle& style,
                        const std::string& title = "panel") {
    std::vector<std::string> titles;
    for (int i = 0; i < count; ++i) {
        std::string t = title;
        t.push_back(' ');
        t.append(std::to_string(i + 1));
        titles.push_back(std::move(t));
    }
    return render::grid_text(render::panel_grid(page, count, columns, true, style), titles, render::TitlePlace::above,
                             std::round(style.title_size * style.scale), style.title_pad * style.scale);
}

}  // namespace

TEST_CASE("grids of 1 to 9 panels keep every title clear of the others and of the panels and the page", "[layout]") {
    for (const Rect page : {Rect{0, 0, 900, 900}, Rect{0, 0, 1200, 600}, Rect{0, 0, 600, 1000}}) {
        for (const float aspect : {0.5f, 1.0f, 2.0f}) {
            render::PanelRowStyle style;
            style.aspect = aspect;
            for (int count = 1; count <= 9; ++count) {
                INFO(page.w << " x " << page.h << ", aspect " << aspect << ", " << count << " panels");
                const int columns = render::best_columns(page, count, true, style);
                REQUIRE(columns >= 1);
                REQUIRE(columns <= count);
                const render::GridText grid = layout(page, count, columns, style);
                REQUIRE(grid.panels.size() == std::size_t(count));
                CHECK(render::text_clash(grid, page).empty());
                for (int i = 0; i < count; ++i) {
                    CHECK(inside(grid.panels[i], page));
                    CHECK(inside(grid.titles[i], page));
                    for (int j = 0; j < count; ++j) {
                        if (j != i) CHECK(apart(grid.titles[i], grid.titles[j]));
                        if (j != i) CHECK(apart(grid.panels[i], grid.panels[j]));
                        CHECK(apart(grid.titles[i], grid.panels[j]));
                    }
                }
            }
        }
    }
}

TEST_CASE("four square panels make 2 x 2 on a square page and a row on a wide one, never 3 + 1", "[layout]") {
    render::PanelRowStyle square;
    CHECK(render::best_columns({0, 0, 800, 800}, 4, true, square) == 2);
    CHECK(render::best_columns({0, 0, 1600, 400}, 4, true, square) == 4);
    CHECK(render::best_columns({0, 0, 400, 1600}, 4, true, square) == 1);
    for (const Rect page : {Rect{0, 0, 800, 800}, Rect{0, 0, 1000, 700}, Rect{0, 0, 700, 1000}, Rect{0, 0, 900, 450}})
        CHECK(render::best_columns(page, 4, true, square) != 3);
    // Three wide panels stay one row on a wide page, as Think Complexity prints them.
    render::PanelRowStyle wide;
    wide.aspect = 65.0f / 32.0f;
    CHECK(render::best_columns({0, 0, 900, 450}, 3, true, wide) == 3);
    // Six square panels on a 3:2 page: 3 x 2.
    CHECK(render::best_columns({0, 0, 900, 600}, 6, true, square) == 3);
}

TEST_CASE("titles too long for their page are found and a page that holds them is named", "[layout]") {
    render::PanelRowStyle style;
    const Rect small{0, 0, 300, 200};
    const std::string long_title = "X -> F[+X]F[-X]+X, F -> FF, n = 7";
    const render::GridText crowded = layout(small, 3, 3, style, long_title);
    const std::string clash = render::text_clash(crowded, small);
    CHECK(clash.find("the title of panel 1") == 0);
    const render::PageSize fits = render::size_that_fits(300, 200, [&](int w, int h) {
        return layout(Rect{0, 0, float(w), float(h)}, 3, 3, style, long_title);
    });
    REQUIRE(fits.width > 300);
    CHECK(fits.height * 300 == Approx(fits.width * 200).margin(300));  // the page's aspect kept
    const Rect page{0, 0, float(fits.width), float(fits.height)};
    const render::GridText roomy = layout(page, 3, 3, style, long_title);
    CHECK(render::text_clash(roomy, page).empty());
    for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j) CHECK(apart(roomy.titles[i], roomy.titles[j]));
}

TEST_CASE("page text clashes where glyphs overlap and where a text leaves its room", "[layout]") {
    const Rect page{0, 0, 200, 100};
    render::PageText text;
    text.panels.push_back({{100, 10, 90, 80}, "the frame"});
    // Two staircases of glyphs whose boxes overlap while no glyph of one meets a glyph of the other.
    text.texts.push_back({{10, 10, 40, 40}, "the first", -1, {{10, 10, 10, 10}, {40, 40, 10, 10}}});
    text.texts.push_back({{10, 10, 40, 40}, "the second", -1, {{40, 10, 10, 10}, {10, 40, 10, 10}}});
    CHECK(render::text_clash(text, page).empty());
    // A glyph of the second moved onto one of the first.
    text.texts[1].parts[0] = {12, 12, 10, 10};
    CHECK(render::text_clash(text, page) == "the first [10, 10, 40 x 40] overlaps the second");
    text.texts[1].parts[0] = {40, 10, 10, 10};
    // Half a pixel of overlap is rounding; more is not.
    text.texts.push_back({{90.4f, 20, 10, 10}, "the third"});
    CHECK(render::text_clash(text, page).empty());
    text.texts.back().box.x = 91;
    CHECK(render::text_clash(text, page) == "the third [91, 20, 10 x 10] overlaps the frame");
    // A legend belongs inside its frame: in it, fine; sticking out, refused before any overlap is named.
    text.texts.back() = {{120, 20, 40, 30}, "the legend", 0, {}};
    CHECK(render::text_clash(text, page).empty());
    text.texts.back().box.y = 70;
    CHECK(render::text_clash(text, page) == "the legend [120, 70, 40 x 30] runs out of the frame");
    text.texts.back().box = {180, 20, 30, 10};
    CHECK(render::text_clash(text, page) == "the legend [180, 20, 30 x 10] runs off the page");
}
