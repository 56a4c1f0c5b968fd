#pragma once
// Drawing arrays the way the book's imshow calls do: each panel one or more
// field layers stacked (Gray-Scott draws A and B), framed, titled.

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "render/field.hpp"
#include "render/image.hpp"
#include "scenes/output.hpp"
#include <nlohmann/json.hpp>

#include "render/layout.hpp"
#include "render/plot.hpp"
#include "scenes/description_names.hpp"
#include "scenes/scene.hpp"

namespace scenes {

// A layer's values, shared rather than copied: a panel list, its copies and
// the frame being drawn hold one set of cells between them (bd-500's film
// copied its 1216 x 500 view three times a frame, 45% of the film's time).
// Made from a vector it owns the cells; view() refers to cells that outlive
// the drawing (a model's grid, drawn at once as a frame).
class LayerCells {
public:
    LayerCells() = default;
    LayerCells(std::vector<double> values)  // NOLINT(google-explicit-constructor): a layer is built from its values
        : cells_(std::make_shared<const std::vector<double>>(std::move(values))) {}
    static LayerCells view(const std::vector<double>& values) {
        LayerCells cells;
        cells.cells_ = std::shared_ptr<const std::vector<double>>(std::shared_ptr<void>(), &values);  // owns nothing
        return cells;
    }
    std::span<const double> span() const {
        return cells_ ? std::span<const double>(*cells_) : std::span<const double>();
    }
    operator std::span<const double>() const { return span(); }  // NOLINT(google-explicit-constructor)
    std::size_t size() const { return span().size(); }
    auto begin() const { return span().begin(); }
    auto end() const { return span().end(); }

private:
    std::shared_ptr<const std::vector<double>> cells_;
};

struct FieldLayer {
    int rows = 0, cols = 0;
    LayerCells values;  // rows * cols, row 0 at the top
    render::FieldStyle style;
    // A colour bar for this layer beside its panel (the first layer's, when
    // a panel has several): its colours and range, usually the style's.
    std::optional<render::ColourBar> colour_bar = {};
};

// Drawing a field layer: its values as floats for the texture and
// llvmpipe's copy of that texture, per cell. Measured with the models'
// own grids: diffusion, Gray-Scott, percolation and forest fire at n = 2000
// (or 1600) with three panels took 47.6, 87.6, 29.5 and 28 bytes a cell,
// this term included.
inline constexpr double field_layer_bytes_per_cell = 2 * sizeof(float);

struct FieldPanel {
    std::string title;
    std::vector<FieldLayer> layers;  // drawn first to last
};

// Samples per pixel a film's page of field panels needs: one when every
// panel's frame lies on whole pixels, else four. Fields are quads drawn
// without multisampling anyway and text carries its own coverage, so only a
// frame edge between pixels needs the samples; on whole pixels one sample
// saves clearing, blending into and resolving four a pixel. Its pixels are
// the same but for rounding: a glyph's edge pixel may blend one level apart
// (tc7-5's figure at scale 1: 4 of 405,000 pixels; a Gray-Scott frame at
// 480 x 520 and 1280 x 720: none), which the film's encoder does not keep.
// Figures keep four samples, so their pixels do not change at all.
int field_page_samples(const std::vector<FieldPanel>& panels, int width, int height, double scale);

// The panels on a white page of the figure's size (scenes/helpers/figure_caption.hpp),
// in rows of [figure] columns or of the count that makes them largest: the
// figure, drawing `panels`, which must outlive it. Throws a SettingError
// for figure.size when the panels' titles do not fit on it.
FigureDrawing field_figure(const std::vector<FieldPanel>& panels, const Description& d, const SceneOptions& options);

// How a panel's two layers are drawn: one draw each, or both in one pass
// (render::draw_field_pair: faster, the same but for rounding; films).
enum class LayerPasses { each, paired };

// The page of `panels` on any surface of its size: clears it and draws.
void paint_field_panels(render::Surface& surface, const std::vector<FieldPanel>& panels, double scale,
                        LayerPasses passes = LayerPasses::each);
// That page as a frame of width x height pixels, with the samples it needs
// (field_page_samples): what a film's frame of field panels is.
FrameDrawing field_page(std::vector<FieldPanel> panels, int width, int height, double scale,
                        LayerPasses passes = LayerPasses::each);

// The text draw_field_panels would draw: the titles and the colour bars'
// tick labels and labels, for render::text_clash.
render::PageText field_panels_text(const render::Rect& area, const std::vector<FieldPanel>& panels, int columns,
                                   double scale);

// What a figure's JSON says of its colour bar: its label, the values at its
// ends, and its entries.
nlohmann::json colour_bar_metadata(const render::ColourBar& bar);

// A colour bar's ticks and label beside field panels: matplotlib's sizes at `scale`.
render::PlotStyle colour_bar_style(double scale);

// The same panels in `columns` columns inside `area` of a surface being
// drawn; with a colour bar beside each panel whose first layer has one.
void draw_field_panels(render::Surface& surface, const render::Rect& area, const std::vector<FieldPanel>& panels,
                       int columns, double scale, LayerPasses passes = LayerPasses::each);

}  // namespace scenes
