#pragma once
// What a figure is drawn on: one interface, several backends. A scene says
// what its figure holds (shapes, text, fields, hexagonal cells, 3-D tubes)
// through these calls; the GL canvas (render/gl/canvas.hpp) turns them into
// pixels for PNG files and film frames, and the vector page
// (render/vector/vector_page.hpp) into paths, glyphs and embedded images for PDF and
// SVG. A later backend is one more class here, not a change to every scene.
// Coordinates are pixels, origin at the top left, y down, on every backend.

#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace render {

// What drawing costs on the GL canvas (render/gl/), for the scenes' memory
// estimates.
//
// The most triangles one GL draw call hands llvmpipe before glFinish. Its
// setup bins the triangles of a draw into scenes and queues up to 64 of them
// (tens of MiB each) while its threads rasterise, so one draw of millions of
// triangles peaked at hundreds of MiB more than its vertices, differently
// from run to run (pl-lsys-3d at depth 10: 324 to 484 MiB; 177 MiB without
// rasteriser threads). Drawn in batches of this many, finishing each, the
// queue holds one batch; the triangles and their order, so the pixels, are
// the same.
inline constexpr long long triangles_per_finish = 1 << 18;
// What that queue may hold on top of the triangles' own vertices, for memory
// estimates: measured 28 to 37 MiB above the vertices on the plant figures
// (pl-lsys-lycopodium at depth 6, pl-lsys-3d's film at depths 7 and 8).
inline constexpr double queued_triangles_bytes = 64.0 * 1024 * 1024;

struct Rect {
    float x = 0, y = 0, w = 0, h = 0;  // top-left corner and size, pixels
    float right() const { return x + w; }
    float bottom() const { return y + h; }
    glm::vec2 centre() const { return {x + w / 2, y + h / 2}; }
};

class Shapes;
class Text;
struct FieldStyle;
struct HexView;
struct Tube;
struct Facet;
struct Camera;
struct Light;

// How overlapping primitives of one Shapes combine.
enum class Coverage {
    each,  // each primitive blends over what is below, overlaps included
    once,  // a pixel the batch covers gets its colour once: a translucent line keeps one shade where its
           // pieces overlap (matplotlib draws a path in one pass)
};

class Surface {
public:
    virtual ~Surface() = default;
    virtual int width() const = 0;
    virtual int height() const = 0;

    // Fills the page with `colour`; on a transparent surface (--transparent)
    // leaves it clear instead, so that only the ink is opaque.
    virtual void background(const glm::vec4& colour) = 0;
    virtual void shapes(const Shapes& shapes, Coverage coverage) = 0;
    virtual void text(const Text& text) = 0;
    // A rows x cols field (row-major, row 0 at the top) filling `where`; see render/field.hpp.
    virtual void field(const Rect& where, int rows, int cols, std::span<const double> values,
                       const FieldStyle& style) = 0;
    // Two layers of one grid, the second over the first (render/field.hpp's
    // draw_field_pair): by default two field() calls; the GL canvas draws
    // both in one pass.
    virtual void field_pair(const Rect& where, int rows, int cols, std::span<const double> first,
                            const FieldStyle& first_style, std::span<const double> second,
                            const FieldStyle& second_style) {
        field(where, rows, cols, first, first_style);
        field(where, rows, cols, second, second_style);
    }
    virtual void hex_cells(const HexView& view, std::span<const glm::ivec2> cells, const glm::vec4& colour) = 0;
    // 3-D tubes and flat facets in `viewport`, one depth-tested picture (render/tubes.hpp).
    virtual void tubes(const Rect& viewport, const std::vector<Tube>& tubes, const std::vector<Facet>& facets,
                       const Camera& camera, const Light& light, int sides) = 0;
    // Until unclip(), only what falls inside `box`, rounded to whole pixels, is drawn.
    virtual void clip(const Rect& box) = 0;
    virtual void unclip() = 0;
};

// The pixels a clip to `box` keeps: its edges rounded to the nearest pixel
// edge (matplotlib's clip box), [x0, x1) x [y0, y1), possibly empty.
struct PixelBox {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
PixelBox clip_box(const Rect& box);

}  // namespace render
