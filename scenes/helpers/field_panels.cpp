#include "scenes/helpers/field_panels.hpp"

#include <cmath>

#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/panel_grid.hpp"

namespace scenes {
namespace {

// The page's panel style: the scale, and the first layer's shape as the panels' aspect.
render::PanelRowStyle page_style(const std::vector<FieldPanel>& panels, double scale) {
    render::PanelRowStyle style;
    style.scale = static_cast<float>(scale);
    const FieldLayer& first = panels.front().layers.front();
    style.aspect = float(first.cols) / float(first.rows);
    return style;
}

bool any_title(const std::vector<FieldPanel>& panels) {
    for (const FieldPanel& p : panels)
        if (!p.title.empty()) return true;
    return false;
}

// Two layers that one pass can draw: the same grid, sampling and table size.
bool pairable(const std::vector<FieldLayer>& layers) {
    return layers.size() == 2 && layers[0].rows == layers[1].rows && layers[0].cols == layers[1].cols &&
           layers[0].style.sampling == layers[1].style.sampling && layers[0].style.colormap &&
           layers[1].style.colormap && layers[0].style.colormap->size() == layers[1].style.colormap->size();
}

bool whole(float v) {
    return v == std::floor(v);
}

}  // namespace

int field_page_samples(const std::vector<FieldPanel>& panels, int width, int height, double scale) {
    const render::PanelRowStyle style = page_style(panels, scale);
    const auto rects = render::panel_grid({0, 0, float(width), float(height)}, static_cast<int>(panels.size()),
                                          static_cast<int>(panels.size()), any_title(panels), style);
    if (!whole(style.frame_width * style.scale)) return 4;
    for (const render::Rect& r : rects)
        if (!whole(r.x) || !whole(r.y) || !whole(r.w) || !whole(r.h)) return 4;
    return 1;
}

namespace {

// Where draw_field_panels puts the panels in `area`, and the style that
// places them (its gaps widened for colour bars).
struct PanelPlaces {
    render::PanelRowStyle style;
    std::vector<render::Rect> rects;
    std::vector<std::string> titles;
};

PanelPlaces place_panels(const render::Rect& area, const std::vector<FieldPanel>& panels, int columns,
                         double scale) {
    PanelPlaces places{page_style(panels, scale), {}, {}};
    for (const FieldPanel& p : panels) places.titles.push_back(p.title);
    const int count = static_cast<int>(panels.size());
    // Colour bars: each panel's beside it, in room taken from the gaps and
    // the right margin (worked out for the panels as they would be without).
    const std::optional<render::ColourBar>& bar = panels.front().layers.front().colour_bar;
    render::Rect fit = area;
    if (bar) {
        const render::Rect plain = render::panel_grid(area, count, columns, any_title(panels), places.style).front();
        const float room = render::colour_bar_room(*bar, plain.w, plain.h, colour_bar_style(scale));
        places.style.gap += room / places.style.scale;
        fit.w = std::max(1.0f, fit.w - room);
    }
    places.rects = render::panel_grid(fit, count, columns, any_title(panels), places.style);
    return places;
}

}  // namespace

render::PageText field_panels_text(const render::Rect& area, const std::vector<FieldPanel>& panels, int columns,
                                   double scale) {
    const PanelPlaces places = place_panels(area, panels, columns, scale);
    const render::PanelRowStyle& style = places.style;
    render::PageText page = render::page_text(render::grid_text(places.rects, places.titles, render::TitlePlace::above,
                                                                std::round(style.title_size * style.scale),
                                                                style.title_pad * style.scale));
    for (std::size_t i = 0; i < panels.size(); ++i)
        if (const auto& bar = panels[i].layers.front().colour_bar)
            render::colour_bar_text(page, places.rects[i], *bar, colour_bar_style(scale), static_cast<int>(i) + 1);
    return page;
}

void draw_field_panels(render::Surface& surface, const render::Rect& area, const std::vector<FieldPanel>& panels,
                       int columns, double scale, LayerPasses passes) {
    const PanelPlaces places = place_panels(area, panels, columns, scale);
    const auto& rects = places.rects;
    const render::PlotStyle bar_style = colour_bar_style(scale);
    for (std::size_t i = 0; i < panels.size(); ++i) {
        const std::vector<FieldLayer>& layers = panels[i].layers;
        if (passes == LayerPasses::paired && pairable(layers)) {
            render::draw_field_pair(surface, rects[i], layers[0].rows, layers[0].cols, layers[0].values, layers[0].style,
                                    layers[1].values, layers[1].style);
            continue;
        }
        for (const FieldLayer& layer : layers)
            render::draw_field(surface, rects[i], layer.rows, layer.cols, layer.values, layer.style);
    }
    render::draw_panel_decorations(surface, rects, places.titles, places.style);
    for (std::size_t i = 0; i < panels.size(); ++i)
        if (const auto& own = panels[i].layers.front().colour_bar)
            render::draw_colour_bar(surface, rects[i], *own, bar_style);
}

nlohmann::json colour_bar_metadata(const render::ColourBar& bar) {
    return {{"label", bar.label}, {"low", bar.low}, {"high", bar.high}, {"entries", bar.colormap.size()}};
}

render::PlotStyle colour_bar_style(double scale) {
    render::PlotStyle style;
    style.scale = static_cast<float>(scale);
    return style;
}

void paint_field_panels(render::Surface& surface, const std::vector<FieldPanel>& panels, double scale,
                        LayerPasses passes) {
    surface.background({1, 1, 1, 1});
    draw_field_panels(surface, {0, 0, float(surface.width()), float(surface.height())}, panels,
                      static_cast<int>(panels.size()), scale, passes);
}

FrameDrawing field_page(std::vector<FieldPanel> panels, int width, int height, double scale, LayerPasses passes) {
    const int samples = field_page_samples(panels, width, height, scale);
    return {[panels = std::move(panels), scale, passes](render::Surface& surface) {
                paint_field_panels(surface, panels, scale, passes);
            },
            samples};
}

FigureDrawing field_figure(const std::vector<FieldPanel>& panels, const Description& d, const SceneOptions& options) {
    const int width = figure_width(d, options), height = figure_height(d, options);
    const double scale = options.scale;
    const render::PanelRowStyle style = page_style(panels, scale);
    const bool titled = any_title(panels);
    const int count = static_cast<int>(panels.size());
    auto columns_in = [&](const render::Rect& area) { return figure_columns(d, area, count, titled, style); };
    require_text_fits(d, options, [&](const render::Rect& area) {
        return field_panels_text(area, panels, columns_in(area), scale);
    });
    const int columns = columns_in({0, 0, float(width), float(height)});
    return {width, height, false, [&panels, scale, columns](render::Surface& surface) {
                surface.background({1, 1, 1, 1});
                draw_field_panels(surface, {0, 0, float(surface.width()), float(surface.height())}, panels, columns,
                                  scale);
            }};
}

}  // namespace scenes
