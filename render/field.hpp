#pragma once
// A scalar field drawn into a rectangle through a colormap, as matplotlib's
// imshow does: row 0 at the top, each value normalised by vmin/vmax and looked
// up in the colormap's 256-entry table, blended over what is below at `alpha`.
// Interpolation happens on the data, before the colormap (matplotlib's
// interpolation_stage="data").

#include <span>
#include <vector>

#include "render/colormap.hpp"
#include "render/image.hpp"
#include "render/surface.hpp"

namespace render {

// The most cells a side of a field the renderer draws as one texture:
// GL 4.5's least GL_MAX_TEXTURE_SIZE, so a description is checked against
// it without opening GL (render/gl/ refuses a context with less).
constexpr int max_texture_side = 16384;

enum class Sampling {
    nearest,  // each cell a flat square: imshow(interpolation="nearest")
    smooth,   // cubic B-spline through the cells: imshow(interpolation="bicubic"), Agg's bicubic filter
};

struct FieldStyle {
    const Colormap* colormap = nullptr;  // required
    double vmin = 0.0;                   // value drawn with the first colour
    double vmax = 1.0;                   // value drawn with the last colour
    float alpha = 1.0f;                  // opacity over what lies below
    Sampling sampling = Sampling::nearest;
};

// Draws a rows x cols field (row-major, row 0 at the top) to fill `where`.
void draw_field(Surface& surface, const Rect& where, int rows, int cols, std::span<const double> values,
                const FieldStyle& style);

// The field as an RGBA image (straight alpha, style.alpha in every pixel),
// for backends that embed it (the vector page): at its own cells with
// nearest sampling, or, smooth, resampled with the same cubic B-spline on
// the data as the GL draw to the pixels of `where` (matplotlib's vector
// backends likewise resample interpolated images to the output's dpi). A
// nearest field with more than max_cells_per_pixel cells a pixel of
// `where` either way is sampled (nearest) down to that many: no zoom a
// reader uses tells them apart, and the image, with the memory and the file
// it takes, stays bounded by the figure's pixels.
inline constexpr int max_cells_per_pixel = 2;
Image field_image(const Rect& where, int rows, int cols, std::span<const double> values, const FieldStyle& style);

// Two layers of one grid, the second over the first, in one pass: both
// values come from one texture fetch and the pair is blended once, where two
// draw_field calls fetch twice and blend twice. Smooth layers on a rectangle
// of whole pixels are resampled on the CPU (the same cubic B-spline) to one
// value a pixel, so the shader fetches once instead of four bilinear times:
// a 480 x 520 Gray-Scott film frame draws in 2.1 ms, against 2.7 ms with the
// spline in the shader and 8.4 ms as two draw_field calls (bench
// draw_smooth_frame_paired and draw_smooth_frame). The colours are
// composited in float and rounded once, so a pixel may differ from two
// draw_field calls, which round twice, by up to 2 levels
// (tests/render/test_field.cpp); films draw this way, figures with
// draw_field, so their pixels stay as recorded. The layers must share their
// sampling and colour-table size.
void draw_field_pair(Surface& surface, const Rect& where, int rows, int cols, std::span<const double> first,
                     const FieldStyle& first_style, std::span<const double> second, const FieldStyle& second_style);

// Where a smooth pair on whole pixels (a film's frame) is resampled: on
// the CPU, a separable cubic B-spline giving one texel a pixel (llvmpipe
// samples on the CPU anyway, and its sampler is the slow part of a frame),
// or by the GPU's sampler, the shader's spline of 4 bilinear fetches.
// automatic: the CPU on llvmpipe, the sampler on any other renderer. The
// two agree but for rounding (tests/render/test_field.cpp).
enum class FieldResampling { automatic, cpu, sampler };
void set_field_resampling(FieldResampling resampling);
FieldResampling field_resampling();

// `texels` (rows x cols of `layers` interleaved channels) resampled by the
// smooth shader's cubic B-spline to one value a pixel of width x height,
// into `resampled`; `across_rows` is scratch. The GL canvas's films and the
// vector page's images both use it.
void spline_resample(const std::vector<float>& texels, int rows, int cols, int layers, int width, int height,
                     std::vector<float>& across_rows, std::vector<float>& resampled);

}  // namespace render
