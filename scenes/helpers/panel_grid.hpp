#pragma once
// A figure's panels in a grid of rows and columns chosen for its size
// ([figure] columns, or the count that makes the panels largest), and the
// check that their titles and captions fit: none overlaps another or a
// panel, or runs off the page. A figure whose text cannot fit at its size is
// refused with a size that holds it.

#include <functional>
#include <string>

#include "render/layout.hpp"
#include "scenes/scene.hpp"

namespace scenes {

// [figure] columns (at most `count`), or render::best_columns.
int figure_columns(const Description& d, const render::Rect& area, int count, bool titled,
                   const render::PanelRowStyle& style);

// Throws a SettingError for figure.size when the text `layout_at` places on
// the figure's drawing area clashes, naming what clashes and a figure size
// (at scale 1, the caption's band included) at which it fits, then `remedy`
// (what else would make it fit).
inline constexpr const char* grid_remedy = "set figure.columns, or shorten the text";
inline constexpr const char* plot_remedy = "set style.font_size and style.label_size smaller, or shorten the labels";
void require_text_fits(const Description& d, const SceneOptions& options,
                       const std::function<render::PageText(const render::Rect& area)>& layout_at,
                       const std::string& remedy = grid_remedy);

// The titles above a panel_grid's panels (its room for titles kept when
// `titled`, whatever the titles are).
render::GridText titled_grid_text(const render::Rect& area, const std::vector<std::string>& titles, int columns,
                                  bool titled, const render::PanelRowStyle& style);

}  // namespace scenes
