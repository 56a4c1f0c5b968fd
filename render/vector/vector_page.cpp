#include "render/vector/vector_page.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "render/gl/canvas.hpp"
#include "render/field.hpp"
#include "render/hex_cells.hpp"
#include "render/shapes.hpp"
#include "render/text.hpp"
#include "render/tubes.hpp"

namespace render {
namespace {

using vector::Path;
using vector::PathStep;

// Every polygon of a page winds counter-clockwise on screen, as its circles
// do (vector::PathStep::circle): the shapes of one nonzero path then make
// their union, whichever way they were given.
void add_polygon(Path& path, std::span<const glm::vec2> points) {
    double area = 0;  // twice the signed area, y down: negative counter-clockwise on screen
    for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::vec2 a = points[i], b = points[(i + 1) % points.size()];
        area += double(a.x) * b.y - double(b.x) * a.y;
    }
    const bool reverse = area > 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const glm::vec2 p = points[reverse ? points.size() - 1 - k : k];
        path.push_back({k == 0 ? PathStep::move : PathStep::line, p});
    }
    path.push_back({PathStep::close});
}

void add_rect(Path& path, const Rect& r) {
    const glm::vec2 corners[] = {{r.x, r.y}, {r.right(), r.y}, {r.right(), r.bottom()}, {r.x, r.bottom()}};
    add_polygon(path, corners);
}

// A line's dashes as cairo takes them: lengths of at least 0, an even
// count (an odd one repeats twice, as the GL backend reads it); empty when
// the pattern is too short to show, which draws solid there too.
std::vector<float> usable_dash(std::span<const float> dash) {
    std::vector<float> pattern;
    for (float d : dash) pattern.push_back(std::max(0.0f, d));
    if (pattern.size() % 2 == 1) pattern.insert(pattern.end(), pattern.begin(), pattern.end());
    float period = 0;
    for (float d : pattern) period += d;
    if (!(period > 1e-3f)) pattern.clear();
    return pattern;
}

// How an op is drawn: what must agree for consecutive ops to share one path.
struct Style {
    enum Kind { fill, even_odd, stroke } kind;
    vector::Cap cap = vector::Cap::butt;
    float width = 0;
    std::vector<float> dash;
    float dash_offset = 0;

    bool operator==(const Style&) const = default;
};

Style style_of(const Shapes& shapes, const Shapes::Op& op) {
    switch (op.kind) {
        case Shapes::Kind::triangle:
        case Shapes::Kind::rect:
        case Shapes::Kind::disc:
        case Shapes::Kind::polygon: return {Style::fill, vector::Cap::butt, 0, {}, 0};
        case Shapes::Kind::frame:
        case Shapes::Kind::ring: return {Style::even_odd, vector::Cap::butt, 0, {}, 0};
        case Shapes::Kind::line: return {Style::stroke, vector::Cap::butt, op.width, {}, 0};
        case Shapes::Kind::round_segment: return {Style::stroke, vector::Cap::round, op.width, {}, 0};
        case Shapes::Kind::polyline: {
            std::vector<float> dash = usable_dash(op.dash(shapes));
            const float offset = dash.empty() ? 0 : op.b;
            return {Style::stroke, op.cap == LineCap::square ? vector::Cap::square : vector::Cap::butt, op.width,
                    std::move(dash), offset};
        }
    }
    return {Style::fill, vector::Cap::butt, 0, {}, 0};
}

// Adds op's outline to `path` (a fill's area, or a stroke's centre line).
void add_op(Path& path, const Shapes& shapes, const Shapes::Op& op) {
    const auto p = op.points(shapes);
    switch (op.kind) {
        case Shapes::Kind::triangle:
        case Shapes::Kind::polygon: add_polygon(path, p); break;
        case Shapes::Kind::rect: add_rect(path, {p[0].x, p[0].y, p[1].x, p[1].y}); break;
        case Shapes::Kind::frame: {
            const Rect r{p[0].x, p[0].y, p[1].x, p[1].y};
            add_rect(path, r);
            const float w = op.width;
            if (2 * w < r.w && 2 * w < r.h) add_rect(path, {r.x + w, r.y + w, r.w - 2 * w, r.h - 2 * w});
            break;
        }
        case Shapes::Kind::disc: path.push_back({PathStep::circle, p[0], op.a}); break;
        case Shapes::Kind::ring:
            path.push_back({PathStep::circle, p[0], op.b});
            if (op.a > 0) path.push_back({PathStep::circle, p[0], op.a});
            break;
        case Shapes::Kind::line:
            path.push_back({PathStep::move, p[0]});
            path.push_back({PathStep::line, p[1]});
            break;
        case Shapes::Kind::round_segment:
            // Joined to the last segment when it starts where that one ended: one
            // stroke along a branch, round where it turns, as the GL's end discs.
            if (path.empty() || path.back().kind != PathStep::line || path.back().at != p[0])
                path.push_back({PathStep::move, p[0]});
            path.push_back({PathStep::line, p[1]});
            break;
        case Shapes::Kind::polyline:
            for (std::size_t i = 0; i < p.size(); ++i) path.push_back({i == 0 ? PathStep::move : PathStep::line, p[i]});
            break;
    }
}

}  // namespace

VectorPage::VectorPage(int width, int height, bool transparent) : transparent_(transparent) {
    page_.width = width;
    page_.height = height;
}

void VectorPage::background(const glm::vec4& colour) {
    page_.items.clear();
    if (transparent_) return;
    Path path;
    add_rect(path, {0, 0, float(page_.width), float(page_.height)});
    page_.items.push_back(vector::Fill{std::move(path), colour});
}

void VectorPage::shapes(const Shapes& shapes, Coverage coverage) {
    const auto& ops = shapes.ops();
    if (ops.empty()) return;
    // Once: the batch is painted opaque in a group laid over the page at its
    // alpha, when the batch has a single alpha (a plot's line); it is then one
    // shade wherever its pieces overlap, as the GL's stencil makes it.
    std::optional<float> group_alpha;
    if (coverage == Coverage::once) {
        const float alpha = ops.front().colour.a;
        bool one = alpha < 1;
        for (const auto& op : ops) one = one && op.colour.a == alpha;
        if (one) group_alpha = alpha;
    }
    if (group_alpha) page_.items.push_back(vector::GroupBegin{});
    for (std::size_t i = 0; i < ops.size();) {
        const Style style = style_of(shapes, ops[i]);
        glm::vec4 colour = ops[i].colour;
        // Ops of one colour and style share a path, which paints their union:
        // the same as painting each when the colour is opaque or a group lays
        // them over the page once.
        const bool merge = colour.a == 1 || group_alpha;
        Path path;
        std::size_t end = i;
        do {
            add_op(path, shapes, ops[end]);
            ++end;
        } while (merge && end < ops.size() && ops[end].colour == colour && style_of(shapes, ops[end]) == style);
        if (group_alpha) colour.a = 1;
        if (style.kind == Style::stroke)
            page_.items.push_back(vector::Stroke{std::move(path), colour, style.width, style.cap, style.dash,
                                                 style.dash_offset});
        else
            page_.items.push_back(vector::Fill{std::move(path), colour,
                                               style.kind == Style::even_odd ? vector::FillRule::even_odd
                                                                             : vector::FillRule::nonzero});
        i = end;
    }
    if (group_alpha) page_.items.push_back(vector::GroupEnd{*group_alpha});
}

namespace {

// Splits a shaped line into runs of one face whose clusters go one way
// through the text (a right-to-left run goes backward), each with the
// characters it draws and cairo's clusters, so that the PDF's text reads
// back in the text's order.
std::vector<vector::Glyphs> glyph_runs(const Text::Line& line) {
    const Font::Shaped& shaped = line.shaped;
    std::vector<std::uint32_t> starts;  // every cluster's first byte, ascending
    for (const Font::ShapedGlyph& g : shaped.glyphs) starts.push_back(g.cluster);
    std::sort(starts.begin(), starts.end());
    starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
    auto end_of = [&](std::uint32_t cluster) {
        const auto next = std::upper_bound(starts.begin(), starts.end(), cluster);
        return next == starts.end() ? static_cast<std::uint32_t>(shaped.text.size()) : *next;
    };
    std::vector<vector::Glyphs> runs;
    const auto& glyphs = shaped.glyphs;
    for (std::size_t i = 0; i < glyphs.size();) {
        // The longest run from i of one face with clusters all ascending or all descending.
        std::size_t j = i + 1;
        int way = 0;  // +1 forward, -1 backward, 0 not known yet
        while (j < glyphs.size() && glyphs[j].face == glyphs[i].face) {
            const int step = glyphs[j].cluster > glyphs[j - 1].cluster ? 1 : glyphs[j].cluster < glyphs[j - 1].cluster ? -1 : 0;
            if (step != 0 && way != 0 && step != way) break;
            if (step != 0) way = step;
            ++j;
        }
        const FontFile& file = line.font->face_file(glyphs[i].face);
        vector::Glyphs run{file.path, file.index, line.font->pixel_size(), line.colour, line.origin,
                           line.rotation_degrees, {}, {}, {}, way < 0};
        std::map<std::uint32_t, int> per_cluster;  // glyphs of each cluster, in the text's order
        for (std::size_t k = i; k < j; ++k) {
            run.glyphs.push_back({glyphs[k].index, glyphs[k].position});
            ++per_cluster[glyphs[k].cluster];
        }
        // The run's clusters must be consecutive in the line for its text to be one piece.
        const auto first = std::lower_bound(starts.begin(), starts.end(), per_cluster.begin()->first);
        if (static_cast<std::size_t>(starts.end() - first) >= per_cluster.size() &&
            std::equal(per_cluster.begin(), per_cluster.end(), first,
                       [](const auto& entry, std::uint32_t start) { return entry.first == start; })) {
            const std::uint32_t from = per_cluster.begin()->first, to = end_of(per_cluster.rbegin()->first);
            run.text = shaped.text.substr(from, to - from);
            for (const auto& [cluster, count] : per_cluster)
                run.clusters.emplace_back(static_cast<int>(end_of(cluster) - cluster), count);
        }
        runs.push_back(std::move(run));
        i = j;
    }
    return runs;
}

}  // namespace

void VectorPage::text(const Text& text) {
    for (const Text::Line& line : text.lines())
        for (vector::Glyphs& run : glyph_runs(line)) page_.items.push_back(std::move(run));
}

void VectorPage::field(const Rect& where, int rows, int cols, std::span<const double> values,
                       const FieldStyle& style) {
    page_.items.push_back(
        vector::Picture{field_image(where, rows, cols, values, style), where, style.sampling == Sampling::smooth});
}

void VectorPage::hex_cells(const HexView& view, std::span<const glm::ivec2> cells, const glm::vec4& colour) {
    // Cells under a pixel across would be more hexagons than the page has
    // pixels to show them: drawn by GL at the page's pixels and embedded as
    // that image, which keeps the file and the memory bounded by the page.
    if (view.size < min_vector_hex_size) {
        Canvas canvas(page_.width, page_.height, canvas_samples);
        canvas.set_transparent(true);
        canvas.background({0, 0, 0, 0});
        const std::vector<glm::ivec2> all(cells.begin(), cells.end());
        draw_hex_cells(canvas, view, all, colour);
        page_.items.push_back(
            vector::Picture{canvas.read(), {0, 0, float(page_.width), float(page_.height)}, false});
        return;
    }
    // The corners as the GL backend places them: exact lattice offsets in half sizes.
    static constexpr int corner[6][2] = {{2, 0}, {1, 1}, {-1, 1}, {-2, 0}, {-1, -1}, {1, -1}};
    const double half = 0.5 * view.size, root3 = std::sqrt(3.0);
    Path path;
    path.reserve(cells.size() * 7);
    for (const glm::ivec2 cell : cells)
        for (int k = 0; k < 6; ++k) {
            const double x = 3.0 * cell.x + corner[k][0], y_up = 2.0 * cell.y + cell.x + corner[k][1];
            const glm::vec2 p{float(view.centre.x + half * x), float(view.centre.y - half * root3 * y_up)};
            path.push_back({k == 0 ? PathStep::move : PathStep::line, p});
            if (k == 5) path.push_back({PathStep::close});
        }
    page_.items.push_back(vector::Fill{std::move(path), colour});
}

void VectorPage::tubes(const Rect& viewport, const std::vector<Tube>& tubes, const std::vector<Facet>& facets,
                       const Camera& camera, const Light& light, int sides) {
    const PixelBox box = clip_box(viewport);
    const int w = box.x1 - box.x0, h = box.y1 - box.y0;
    if (w < 1 || h < 1) return;
    Canvas canvas(w, h, canvas_samples, true);
    canvas.set_transparent(true);
    canvas.background({0, 0, 0, 0});
    draw_tubes(canvas, {0, 0, float(w), float(h)}, tubes, facets, camera, light, sides);
    page_.items.push_back(vector::Picture{canvas.read(), {float(box.x0), float(box.y0), float(w), float(h)}, true});
}

void VectorPage::clip(const Rect& box) { page_.items.push_back(vector::Clip{clip_box(box)}); }

void VectorPage::unclip() { page_.items.push_back(vector::Unclip{}); }

}  // namespace render
