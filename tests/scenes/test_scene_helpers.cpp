// The scenes' shared helpers and registry.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <tuple>

#include "description/catalog.hpp"
#include "description/description.hpp"
#include "render/colormap.hpp"
#include "render/gl/canvas.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/scene.hpp"

TEST_CASE("every catalog description names a known scene", "[scenes]") {
    const auto& known = scenes::all_scenes();
    for (const auto& file : description::catalog_files()) {
        INFO(file.string());
        const description::Description d = description::load_description(file);
        CHECK(std::any_of(known.begin(), known.end(), [&](const auto& s) { return s.name == d.scene; }));
    }
}

TEST_CASE("field statistics are exact for a known field", "[scenes]") {
    sim::Grid<double> field(2, 2);
    field(0, 0) = 1;
    field(0, 1) = 2;
    field(1, 0) = 3;
    field(1, 1) = -2;
    const auto stats = scenes::field_statistics(field);
    CHECK(stats["min"] == -2.0);
    CHECK(stats["max"] == 3.0);
    CHECK(stats["sum"] == 4.0);
    CHECK(stats["mean"] == 1.0);
    // SHA-256 of the 32 bytes of four little-endian doubles, computed independently:
    // python3 -c "import hashlib,struct; print(hashlib.sha256(struct.pack('<4d',1,2,3,-2)).hexdigest())"
    CHECK(scenes::state_hash(field) == "2bac1189f87925bde11530a00007af4b28eea3115bd5cc1a6c0a6e4969380744");
}

TEST_CASE("a bad drawing setting or reference value is refused in phase 1, naming its key", "[scenes]") {
    // read_scene is phase 1: a SettingError from it means no model step was taken.
    struct Case {
        const char* id;
        const char* set;
        const char* key;
        const char* message;
    };
    const Case cases[] = {
        {"pl-lsys-3d", "style.sides=0", "style.sides", "style.sides = 0 is not allowed: an integer from 3 to 256"},
        {"tc7-phase", "p_c=1e308", "params.p_c", "p_c = 1e+308 is not allowed: "},
        {"pl-lsys-gallery", "plants=[{axiom=\"F\", angle=1e308}]", "params.plants[0].angle",
         "plants[0].angle = 1e+308 is not allowed: "},
        {"tc7-1", "style.colormap=\"jet\"", "style.colormap", "style.colormap = 'jet' is not allowed: one of "},
    };
    for (const Case& c : cases) {
        INFO(c.id << " --set " << c.set);
        const description::Description d = description::load_description(description::resolve_figure(c.id), {c.set});
        try {
            scenes::read_scene(d, scenes::SceneOptions{});
            FAIL("phase 1 accepted it");
        } catch (const description::SettingError& e) {
            CHECK(e.key() == c.key);
            CHECK_THAT(e.what(), Catch::StartsWith(c.message));
        }
    }
}

TEST_CASE("every catalog figure passes phase 1 as described", "[scenes]") {
    for (const auto& file : description::catalog_files()) {
        INFO(file.string());
        const description::Description d = description::load_description(file);
        CHECK_NOTHROW(scenes::read_scene(d, scenes::SceneOptions{}));
    }
}

TEST_CASE("a film's page of field panels takes one sample a pixel where its frames lie on whole pixels", "[scenes]") {
    scenes::FieldPanel panel{"step 10", {}};
    std::vector<double> values(36);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::sin(0.7 * double(i));
    panel.layers.push_back({6, 6, values, {&render::colormap("Reds"), -1, 1, 0.7f, render::Sampling::smooth}});
    const std::vector<scenes::FieldPanel> page = {panel};
    // At scale 1 the frames lie on whole pixels (a film's frames); at 0.5 their 0.5-pixel lines do not.
    CHECK(scenes::field_page_samples(page, 480, 520, 1.0) == 1);
    CHECK(scenes::field_page_samples(page, 240, 260, 0.5) == 4);
    const auto drawn = [&](render::Canvas& canvas, double scale) {
        scenes::paint_field_panels(canvas, page, scale);
        return canvas.read().rgba;
    };
    for (const auto& [width, height, scale] : {std::tuple{480, 520, 1.0}, std::tuple{1280, 720, 1.0}}) {
        render::Canvas one(width, height, 1), four(width, height, 4);
        CHECK(drawn(one, scale) == drawn(four, scale));
    }
    render::Canvas one(240, 260, 1), four(240, 260, 4);
    CHECK(drawn(one, 0.5) != drawn(four, 0.5));
}

TEST_CASE("plots side by side make room for their measured y tick labels", "[plot][layout]") {
    // Two plots whose y tick labels ("0.5920") are wider than the gap matplotlib's fractions leave at 640 x 480.
    render::Axes narrow, wide;
    narrow.x_range = wide.x_range = std::pair{0.0, 1.0};
    narrow.y_range = std::pair{0.0, 1.0};
    wide.y_range = std::pair{0.5915, 0.5960};
    wide.y_label = "estimate of p_c";
    const render::PlotStyle style;
    const render::Rect page{0, 0, 640, 480};
    const auto plain = render::plot_row(640, 480, 2, style);
    render::PageText crowded;
    render::axes_text(crowded, plain[0], narrow, style, 1);
    render::axes_text(crowded, plain[1], wide, style, 2);
    const std::string clash = render::text_clash(crowded, page);
    CHECK(clash.find("of plot 2") != std::string::npos);
    CHECK(clash.find("overlaps the frame of plot 1") != std::string::npos);
    // The page's own layout widens the gap: nothing clashes, and the frames stay on the page.
    const render::PageText roomy = scenes::plot_row_text(page, {narrow, wide}, style);
    CHECK(render::text_clash(roomy, page).empty());
    REQUIRE(roomy.panels.size() == 2);
    CHECK(roomy.panels[1].box.x - roomy.panels[0].box.right() > plain[1].x - plain[0].right());
    CHECK(roomy.panels[1].box.right() <= 640);
    // Plots whose labels fit keep matplotlib's fractions exactly.
    const render::PageText same = scenes::plot_row_text(page, {narrow, narrow}, style);
    CHECK(same.panels[0].box.x == plain[0].x);
    CHECK(same.panels[1].box.x == plain[1].x);
    CHECK(same.panels[1].box.w == plain[1].w);
}
