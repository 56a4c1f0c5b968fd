#pragma once
// Vector output (PDF, SVG) through cairo, built as a module of its own
// (render/vector/cairo.cpp, libfiggen_vector.so) that the program opens
// only when a figure is written as PDF or SVG: libcairo and the X, font and
// image libraries behind it stay out of every other process.
//
// The program draws a figure on a VectorPage (render/vector/vector_page.hpp),
// which records it as the plain data below: filled and stroked paths, lines
// of glyphs from a font file, embedded images, clips and groups, in pixels
// (top-left origin, y down) of a width x height page. The module turns a
// page into a file and never touches a path it is not given: it writes to
// the descriptor the program opened (AtomicFile) and reads only the font
// files the page names, which the program chose.

#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include <utility>

#include <glm/glm.hpp>

#include "render/image.hpp"
#include "render/surface.hpp"
#include "render/vector/vector_abi.h"

namespace render::vector {

// The module's formats (vector_abi.h), by name.
enum class Format : int { pdf = FIGGEN_VECTOR_PDF, svg = FIGGEN_VECTOR_SVG };

// One piece of a path.
struct PathStep {
    enum Kind : std::uint8_t {
        move,    // starts a subpath at `at`
        line,    // a straight line to `at`
        close,   // back to the subpath's start
        circle,  // a whole circle about `at` of `radius`, counter-clockwise on screen, as a subpath of its own
    } kind;
    glm::vec2 at{0, 0};
    float radius = 0;
};
using Path = std::vector<PathStep>;

enum class FillRule { nonzero, even_odd };
enum class Cap { butt, square, round };

struct Fill {
    Path path;
    glm::vec4 colour;  // straight alpha
    FillRule rule = FillRule::nonzero;
};

struct Stroke {
    Path path;
    glm::vec4 colour;
    float width = 1;
    Cap cap = Cap::butt;    // round strokes also join round; the others mitre up to a limit of 2, then round
    std::vector<float> dash;  // on, off, ... pixels (an even count); empty: solid
    float dash_offset = 0;
};

// A run of glyphs of one face, as the PNG drew them.
struct Glyphs {
    std::string font_path;  // the font file the glyph indices are of
    int font_index = 0;     // the face within it (a .ttc collection holds several)
    float pixel_size;       // em size, pixels
    glm::vec4 colour;
    glm::vec2 origin;         // the line's start on the baseline
    float rotation_degrees;   // counter-clockwise on screen about the origin
    struct Glyph {
        unsigned index;      // in that face
        glm::vec2 position;  // from the origin in the line's frame, pixels, y down
    };
    std::vector<Glyph> glyphs;  // left to right on the page
    // The characters the glyphs draw, as UTF-8, for text search and copying
    // (PDF's ActualText), and how they correspond: cairo's clusters, each
    // {bytes, glyphs}, in the text's order; `backward` when the glyphs run
    // right to left through the text. Empty text: the glyphs alone.
    std::string text;
    std::vector<std::pair<int, int>> clusters;
    bool backward = false;
};

struct Picture {
    Image image;  // RGBA, straight alpha
    Rect where;   // the image fills this rectangle
    bool smooth;  // false: nearest sampling, so that a viewer never blurs the cells
};

struct Clip {
    PixelBox box;  // until an Unclip
};
struct Unclip {};

// What lies between GroupBegin and GroupEnd is drawn opaque and then laid
// over the page once at `alpha`: a translucent line keeps one shade where
// its pieces overlap.
struct GroupBegin {};
struct GroupEnd {
    float alpha;
};

using Item = std::variant<Fill, Stroke, Glyphs, Picture, Clip, Unclip, GroupBegin, GroupEnd>;

struct Page {
    int width = 0, height = 0;  // pixels: PDF's page is 0.72 pt a pixel (the PNG at 100 dpi), SVG's a CSS px
    std::vector<Item> items;    // painted in order
    std::string title;          // the document's title
    std::string creator;        // "figgen 1.2.3"
};

// The PDF's and SVG's stage: a vector page (its paths, and its images at
// most render::max_cells_per_pixel cells a pixel each way, hexagons under a
// pixel drawn as one image) and cairo writing it, one format at a time,
// after the PNG's canvas has gone. Measured above the same run without
// them: 1.1 to 9.0 MiB on six catalog figures (900 x 450 to 1000 x 620),
// 13.0 MiB for tc7-1's three fields of 3000 x 3000 cells; with a margin,
// 16 MiB and 64 bytes a pixel of the figure. A plant's paths are counted by
// its own estimate (a segment's bytes there are far more than its path's).
constexpr double page_bytes = 16.0 * 1024 * 1024;
constexpr double page_bytes_per_pixel = 64.0;
// The most a PDF or SVG of width x height pixels may take: 16 bytes a pixel
// and 1 MiB (docs/outputs.md lists what the catalog's take). A file that
// would pass it stops with an error before more is written (write's
// max_bytes), so the disk estimate holds.
inline double file_bytes(int width, int height) {
    return 16.0 * width * height + 1024.0 * 1024.0;
}

// Writes `page` as `format` to `fd` (open for writing, at its start)
// through the module, opened on the first call; `shown` is the path errors
// name. Throws std::runtime_error with one line: the module cannot be
// opened, cairo failed (a full disk included), or the file would pass
// `max_bytes`, before writing more than that. The page crosses into the
// module in plain C types (render/vector/vector_abi.h), one item at a time.
void write(int fd, const std::filesystem::path& shown, Format format, const Page& page, std::uint64_t max_bytes);

// Starts opening the module on a thread of its own (see render::preload_gl).
void preload();

}  // namespace render::vector
