#pragma once
// A caption beneath the figure ([figure] caption = "title" or "original"):
// the description's title, or the printed figure's own caption
// (original_caption) in its document's language and script, wrapped to
// the figure's width in a band at the bottom. The band is taken from the
// figure's size, not added to it: the scene draws in what is left above, so
// the PNG is still the size asked for.

#include <string>
#include <vector>

#include "scenes/scene.hpp"

namespace scenes {

struct FigureCaption {
    std::vector<std::string> lines;  // as wrapped; empty: no caption
    std::string language;            // for the fallback faces and glyph forms
    float font_pixels = 0;
    float margin = 0;                // above, below and on each side of the lines, pixels
    int band = 0;                    // rows the caption takes at the figure's bottom
};

// The caption of `d` at `scale` on a figure of width x height pixels. Throws
// a SettingError for figure.caption when it does not fit: a word wider than
// the figure, or a band of more than a third of its height; the message
// gives a size that would fit. Measures with FreeType only: no GL is opened.
FigureCaption figure_caption(const Description& d, int width, int height, double scale);

// The figure's size at the options' scale; the height less the caption's band.
int figure_width(const Description& d, const SceneOptions& options);
int figure_height(const Description& d, const SceneOptions& options);

// `scene` (drawn width x (height - band)) with the caption beneath it.
FigureDrawing with_caption(FigureDrawing scene, const FigureCaption& caption);

}  // namespace scenes
