#include "scenes/helpers/panel_grid.hpp"

#include <algorithm>
#include <cmath>

#include "scenes/helpers/figure_caption.hpp"

namespace scenes {

int figure_columns(const Description& d, const render::Rect& area, int count, bool titled,
                   const render::PanelRowStyle& style) {
    if (count <= 1) return 1;
    if (d.columns > 0) return std::min(d.columns, count);
    return render::best_columns(area, count, titled, style);
}

render::GridText titled_grid_text(const render::Rect& area, const std::vector<std::string>& titles, int columns,
                                  bool titled, const render::PanelRowStyle& style) {
    return render::grid_text(render::panel_grid(area, static_cast<int>(titles.size()), columns, titled, style), titles,
                             render::TitlePlace::above, std::round(style.title_size * style.scale),
                             style.title_pad * style.scale);
}

void require_text_fits(const Description& d, const SceneOptions& options,
                       const std::function<render::PageText(const render::Rect& area)>& layout_at,
                       const std::string& remedy) {
    const int width = figure_width(d, options), height = figure_height(d, options);
    const render::Rect area{0, 0, float(width), float(height)};
    const std::string clash = render::text_clash(layout_at(area), area);
    if (clash.empty()) return;
    const int band = scaled(d.height, options.scale) - height;  // the caption's, beneath
    // No larger than a size the user could give (in pixels at this scale).
    const int most = static_cast<int>(std::floor(description::max_figure_side * options.scale));
    const render::PageSize fits = render::size_that_fits(
        width, height + band,
        [&](int w, int h) { return layout_at(render::Rect{0, 0, float(w), float(std::max(1, h - band))}); }, most);
    // std::string("["): GCC 12 warns (-Wrestrict, a false alarm) of "[" + a temporary here.
    const std::string size = std::string("[") + std::to_string(d.width) + ", " + std::to_string(d.height) + "]";
    std::string allowed = "a size at which the figure's text fits: at " + std::to_string(width) + " x " +
                          std::to_string(height + band) + " pixels " + clash;
    if (fits.width > 0) {
        const auto unscaled = [&](int pixels) { return std::to_string(int(std::ceil(pixels / options.scale))); };
        allowed += "; [" + unscaled(fits.width) + ", " + unscaled(fits.height) + "] or larger holds them";
    } else {
        allowed += "; no size up to 8 times as large (each side at most " + std::to_string(description::max_figure_side) +
                   ") holds them";
    }
    throw SettingError("figure.size", size, allowed + " (or " + remedy + ")");
}

}  // namespace scenes
