#include "scenes/helpers/figure_caption.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "render/font_fallback.hpp"
#include "render/text.hpp"

namespace scenes {
namespace {

constexpr float caption_size = 15;    // pixels at scale 1: matplotlib's 11 pt at 100 dpi
constexpr float caption_margin = 8;   // pixels at scale 1
constexpr int most_of_height = 3;     // the band takes at most a third of the figure

// The page above the caption, as the scene sees it: the same surface, its
// height the scene's. The scene's area starts at the page's top left, so
// nothing is moved; the background it paints fills the whole page.
class Above final : public render::Surface {
public:
    Above(render::Surface& page, int height) : page_(page), height_(height) {}
    int width() const override { return page_.width(); }
    int height() const override { return height_; }
    void background(const glm::vec4& colour) override { page_.background(colour); }
    void shapes(const render::Shapes& shapes, render::Coverage coverage) override { page_.shapes(shapes, coverage); }
    void text(const render::Text& text) override { page_.text(text); }
    void field(const render::Rect& where, int rows, int cols, std::span<const double> values,
               const render::FieldStyle& style) override {
        page_.field(where, rows, cols, values, style);
    }
    void field_pair(const render::Rect& where, int rows, int cols, std::span<const double> first,
                    const render::FieldStyle& first_style, std::span<const double> second,
                    const render::FieldStyle& second_style) override {
        page_.field_pair(where, rows, cols, first, first_style, second, second_style);
    }
    void hex_cells(const render::HexView& view, std::span<const glm::ivec2> cells, const glm::vec4& colour) override {
        page_.hex_cells(view, cells, colour);
    }
    void tubes(const render::Rect& viewport, const std::vector<render::Tube>& tubes,
               const std::vector<render::Facet>& facets, const render::Camera& camera, const render::Light& light,
               int sides) override {
        page_.tubes(viewport, tubes, facets, camera, light, sides);
    }
    void clip(const render::Rect& box) override { page_.clip(box); }
    void unclip() override { page_.unclip(); }

private:
    render::Surface& page_;
    const int height_;
};

std::string size_text(int width, int height) { return std::to_string(width) + " x " + std::to_string(height); }

}  // namespace

FigureCaption figure_caption(const Description& d, int width, int height, double scale) {
    FigureCaption caption;
    if (d.figure_caption == "none") return caption;
    const std::string& text = d.figure_caption == "title" ? d.title : d.original_caption;
    if (text.empty()) return caption;
    caption.language = d.figure_caption == "original" ? d.language : "";
    if (!caption.language.empty() && !render::known_language(caption.language))
        throw SettingError("description.language", "\"" + caption.language + "\"",
                           "a language fontconfig knows, e.g. \"zh-cn\", \"zh-tw\", \"ja\", \"ko\" or \"en\"");
    caption.font_pixels = std::round(caption_size * static_cast<float>(scale));
    caption.margin = std::round(caption_margin * static_cast<float>(scale));
    const render::Font font(std::max(caption.font_pixels, 1.0f));
    const float room = static_cast<float>(width) - 2 * caption.margin;
    caption.lines = render::wrap(font, text, std::max(room, 1.0f), caption.language);
    float widest = 0;
    for (const std::string& line : caption.lines) widest = std::max(widest, font.width(line, caption.language));
    const int lines = static_cast<int>(caption.lines.size());
    caption.band = static_cast<int>(std::ceil(lines * font.line_height() + 2 * caption.margin));
    if (widest > room || most_of_height * caption.band > height) {
        // The size that fits: wide enough for the widest word, and tall
        // enough for the lines that width gives.
        const int need_width = std::max(width, static_cast<int>(std::ceil(widest + 2 * caption.margin)));
        const auto at_need = need_width == width ? caption.lines
                                                 : render::wrap(font, text, static_cast<float>(need_width) - 2 * caption.margin,
                                                                caption.language);
        const int need_band =
            static_cast<int>(std::ceil(static_cast<float>(at_need.size()) * font.line_height() + 2 * caption.margin));
        const int need_height = std::max(height, most_of_height * need_band);
        const std::string allowed = "a figure whose caption fits in a third of its height: its " +
                                    std::to_string(lines) + " line(s) take " + std::to_string(caption.band) + " px; ";
        const int most = description::max_figure_side;
        const std::string remedy = need_width <= most && need_height <= most
                                       ? "--size " + std::to_string(need_width) + "x" + std::to_string(need_height) +
                                             " or larger fits them, or caption = \"none\""
                                       : "no size fits them (a figure is at most " + std::to_string(most) + " x " +
                                             std::to_string(most) + "): a shorter text, or caption = \"none\"";
        throw SettingError("figure.caption", "\"" + d.figure_caption + "\" at " + size_text(width, height),
                           allowed + remedy);
    }
    return caption;
}

int figure_width(const Description& d, const SceneOptions& options) { return scaled(d.width, options.scale); }

int figure_height(const Description& d, const SceneOptions& options) {
    const int width = scaled(d.width, options.scale), height = scaled(d.height, options.scale);
    return std::max(2, height - figure_caption(d, width, height, options.scale).band);
}

FigureDrawing with_caption(FigureDrawing scene, const FigureCaption& caption) {
    if (caption.lines.empty()) return scene;
    const int scene_height = scene.height;
    scene.height += caption.band;
    scene.draw = [draw = std::move(scene.draw), caption, scene_height, width = scene.width](render::Surface& surface) {
        Above above(surface, scene_height);
        draw(above);
        render::Font& font = render::font_of_size(caption.font_pixels);
        render::Text text;
        float baseline = static_cast<float>(scene_height) + caption.margin + font.ascender();
        for (const std::string& line : caption.lines) {
            text.add(font, line, {static_cast<float>(width) / 2, baseline}, {0, 0, 0, 1}, render::Align::centre,
                     render::Baseline::baseline, 0, caption.language);
            baseline += font.line_height();
        }
        text.draw(surface);
    };
    return scene;
}

}  // namespace scenes
