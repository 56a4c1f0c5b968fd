#include "render/field.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>


namespace render {
namespace {

// The smooth shader's cubic B-spline, evaluated on the CPU at the centres of
// a width x height block of pixels: the 4 taps and weights of each column
// and row once, then 4 taps along the field's rows and 4 down the columns.
// llvmpipe's sampler spends about 0.4 ms of a 480 x 520 frame on each of the
// shader's 4 bilinear fetches; these two passes take a fraction of that and
// leave the shader one texel fetch a pixel.
struct Taps {
    int index[4];
    float weight[4];
};

std::vector<Taps> spline_taps(int pixels, int cells) {
    std::vector<Taps> taps(static_cast<std::size_t>(pixels));
    for (int i = 0; i < pixels; ++i) {
        // As the shader: the pixel centre in cell units, cell centres at half-integers.
        const double at = (i + 0.5) * cells / pixels - 0.5, base = std::floor(at), u = at - base, s = 1.0 - u;
        const double weights[4] = {s * s * s / 6.0, (4.0 - 6.0 * u * u + 3.0 * u * u * u) / 6.0,
                                   (4.0 - 6.0 * s * s + 3.0 * s * s * s) / 6.0, u * u * u / 6.0};
        for (int k = 0; k < 4; ++k) {
            taps[i].index[k] = std::clamp(static_cast<int>(base) - 1 + k, 0, cells - 1);  // edge cells repeat
            taps[i].weight[k] = static_cast<float>(weights[k]);
        }
    }
    return taps;
}

}  // namespace

void spline_resample(const std::vector<float>& texels, int rows, int cols, int layers, int width, int height,
                     std::vector<float>& across_rows, std::vector<float>& resampled) {
    const auto across = spline_taps(width, cols), down = spline_taps(height, rows);
    const std::size_t n = static_cast<std::size_t>(layers), line = static_cast<std::size_t>(width) * n;
    across_rows.resize(static_cast<std::size_t>(rows) * line);
    for (int r = 0; r < rows; ++r) {
        const float* row = texels.data() + static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) * n;
        float* to = across_rows.data() + static_cast<std::size_t>(r) * line;
        for (int i = 0; i < width; ++i) {
            const Taps& t = across[static_cast<std::size_t>(i)];
            for (std::size_t l = 0; l < n; ++l)
                to[i * n + l] = t.weight[0] * row[t.index[0] * n + l] + t.weight[1] * row[t.index[1] * n + l] +
                                t.weight[2] * row[t.index[2] * n + l] + t.weight[3] * row[t.index[3] * n + l];
        }
    }
    resampled.resize(static_cast<std::size_t>(height) * line);
    for (int j = 0; j < height; ++j) {
        const Taps& t = down[static_cast<std::size_t>(j)];
        const float* a = across_rows.data() + static_cast<std::size_t>(t.index[0]) * line;
        const float* b = across_rows.data() + static_cast<std::size_t>(t.index[1]) * line;
        const float* c = across_rows.data() + static_cast<std::size_t>(t.index[2]) * line;
        const float* d = across_rows.data() + static_cast<std::size_t>(t.index[3]) * line;
        float* to = resampled.data() + static_cast<std::size_t>(j) * line;
        for (std::size_t x = 0; x < line; ++x)
            to[x] = t.weight[0] * a[x] + t.weight[1] * b[x] + t.weight[2] * c[x] + t.weight[3] * d[x];
    }
}

namespace {

FieldResampling& resampling_setting() {
    static FieldResampling setting = FieldResampling::automatic;
    return setting;
}

void check_layer(int rows, int cols, std::span<const double> values, const FieldStyle& style, const char* what) {
    if (rows < 1 || cols < 1 || values.size() != static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols))
        throw std::invalid_argument(std::string(what) + ": " + std::to_string(values.size()) + " values do not fill " +
                                    std::to_string(rows) + "x" + std::to_string(cols) + " cells");
    if (!style.colormap) throw std::invalid_argument(std::string(what) + ": no colormap");
    if (!(style.vmax > style.vmin)) throw std::invalid_argument(std::string(what) + ": vmax must exceed vmin");
}

}  // namespace

void set_field_resampling(FieldResampling resampling) { resampling_setting() = resampling; }
FieldResampling field_resampling() { return resampling_setting(); }

Image field_image(const Rect& where, int rows, int cols, std::span<const double> values, const FieldStyle& style) {
    check_layer(rows, cols, values, style, "field_image");
    const double vmin = style.vmin, span = style.vmax - style.vmin;
    std::vector<float> t(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) t[i] = static_cast<float>((values[i] - vmin) / span);
    int width = cols, height = rows;
    const int pixels_w = std::max(1, static_cast<int>(std::lround(where.w)));
    const int pixels_h = std::max(1, static_cast<int>(std::lround(where.h)));
    if (style.sampling == Sampling::smooth && (pixels_w != cols || pixels_h != rows)) {
        std::vector<float> across, resampled;
        spline_resample(t, rows, cols, 1, pixels_w, pixels_h, across, resampled);
        t = std::move(resampled);
        width = pixels_w, height = pixels_h;
    } else if (cols > max_cells_per_pixel * pixels_w || rows > max_cells_per_pixel * pixels_h) {
        // Denser than any zoom shows: nearest samples at max_cells_per_pixel a pixel each way.
        width = std::min(cols, max_cells_per_pixel * pixels_w), height = std::min(rows, max_cells_per_pixel * pixels_h);
        std::vector<float> sampled(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
        for (int r = 0; r < height; ++r) {
            const int from_r = static_cast<int>((r + 0.5) * rows / height);
            for (int c = 0; c < width; ++c)
                sampled[static_cast<std::size_t>(r) * width + c] =
                    t[static_cast<std::size_t>(from_r) * cols + static_cast<std::size_t>((c + 0.5) * cols / width)];
        }
        t = std::move(sampled);
    }
    Image image(width, height);
    const std::uint8_t alpha = static_cast<std::uint8_t>(std::lround(std::clamp(style.alpha, 0.0f, 1.0f) * 255));
    for (std::size_t i = 0; i < t.size(); ++i) {
        // As the shader: entry floor(t N) clipped; a NaN (which a checked model never gives) takes the first.
        const glm::vec3 c = style.colormap->at(std::isnan(t[i]) ? 0.0 : double(t[i]));
        std::uint8_t* px = &image.rgba[4 * i];
        for (int k = 0; k < 3; ++k) px[k] = static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255));
        px[3] = alpha;
    }
    return image;
}

void draw_field(Surface& surface, const Rect& where, int rows, int cols, std::span<const double> values,
                const FieldStyle& style) {
    check_layer(rows, cols, values, style, "draw_field");
    surface.field(where, rows, cols, values, style);
}

void draw_field_pair(Surface& surface, const Rect& where, int rows, int cols, std::span<const double> first,
                     const FieldStyle& first_style, std::span<const double> second, const FieldStyle& second_style) {
    check_layer(rows, cols, first, first_style, "draw_field_pair");
    check_layer(rows, cols, second, second_style, "draw_field_pair");
    if (first_style.sampling != second_style.sampling || first_style.colormap->size() != second_style.colormap->size())
        throw std::invalid_argument("draw_field_pair: the layers differ in sampling or colour-table size");
    surface.field_pair(where, rows, cols, first, first_style, second, second_style);
}

}  // namespace render
