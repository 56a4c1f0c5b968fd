// The vector module (render/vector/vector.hpp): a page of paths, glyphs and images
// written as PDF or SVG through cairo.
//
// Glyphs come from the very font file and glyph indices the PNG drew, through
// cairo's FreeType backend, so cairo embeds them as a TrueType (CID) subset,
// never as Type 3 bitmaps; hinting is off, so their outlines and advances
// are the font's own. Images keep their pixels: nearest-sampled fields are
// marked so (PDF /Interpolate false, SVG image-rendering), smooth ones not.

#include <unistd.h>

#include <cairo-ft.h>
#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <cstdint>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/vector/vector_abi.h"

namespace {

// What the write callback needs: the descriptor, and the first error it met.
struct Sink {
    int fd;
    std::uint64_t max_bytes;
    std::string* held = nullptr;  // SVG: kept here, to be marked before it is written (mark_nearest)
    std::uint64_t written = 0;
    int error = 0;
    bool too_large = false;
};

bool write_all(Sink& sink, const unsigned char* data, std::size_t length) {
    while (length > 0) {
        const ssize_t n = ::write(sink.fd, data, length);
        if (n < 0) {
            if (errno == EINTR) continue;
            sink.error = errno;
            return false;
        }
        data += n;
        length -= static_cast<std::size_t>(n);
    }
    return true;
}

cairo_status_t write_to_fd(void* closure, const unsigned char* data, unsigned int length) {
    auto* sink = static_cast<Sink*>(closure);
    if (sink->written + length > sink->max_bytes) {
        sink->too_large = true;
        return CAIRO_STATUS_WRITE_ERROR;
    }
    sink->written += length;
    if (sink->held) {
        sink->held->append(reinterpret_cast<const char*>(data), length);
        return CAIRO_STATUS_SUCCESS;
    }
    return write_all(*sink, data, length) ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

// cairo 1.16 (Debian 12's) writes no SVG attribute for a nearest-sampled
// image (1.17.8 and later write image-rendering themselves), so a viewer
// would blur a field's cells. Its images come out as <image id="imageN" ...>
// once each, in the order the page paints them: this marks those of the
// nearest pictures, given in the same order. Should the count differ (another
// cairo), the SVG is left as cairo wrote it.
void mark_nearest(std::string& svg, const std::vector<bool>& nearest) {
    std::vector<std::size_t> at;
    for (std::size_t p = svg.find("<image "); p != std::string::npos; p = svg.find("<image ", p + 1)) at.push_back(p);
    if (at.size() != nearest.size()) return;
    static const std::string mark = "<image style=\"image-rendering:optimizeSpeed;image-rendering:pixelated\" ";
    for (std::size_t k = at.size(); k-- > 0;)
        if (nearest[k]) svg.replace(at[k], 7, mark);
}

[[noreturn]] void fail(const std::string& shown, const std::string& what) {
    throw std::runtime_error("cannot write " + shown + ": " + what);
}

void check(cairo_status_t status, const Sink& sink, const std::string& shown) {
    if (status == CAIRO_STATUS_SUCCESS) return;
    if (status == CAIRO_STATUS_WRITE_ERROR && sink.too_large)
        fail(shown, "it would take more than the " + std::to_string(sink.max_bytes) + " bytes allowed for it");
    if (status == CAIRO_STATUS_WRITE_ERROR && sink.error != 0) fail(shown, std::strerror(sink.error));
    fail(shown, std::string("cairo: ") + cairo_status_to_string(status));
}

// FreeType's library for the module's faces, made on first use and kept:
// cairo may hold a face in its cache past the page that loaded it.
FT_Library freetype(const std::string& shown) {
    static FT_Library library = [] {
        FT_Library l = nullptr;
        return FT_Init_FreeType(&l) == 0 ? l : nullptr;
    }();
    if (!library) fail(shown, "cannot start FreeType");
    return library;
}

// cairo font faces, one per font file of the page; each FreeType face is
// released by cairo when its font face goes.
class Fonts {
public:
    explicit Fonts(const std::string& shown) : shown_(shown) {}
    ~Fonts() {
        for (auto& [file, face] : faces_) cairo_font_face_destroy(face);
    }
    Fonts(const Fonts&) = delete;
    Fonts& operator=(const Fonts&) = delete;

    cairo_font_face_t* face(const std::string& path, int index) {
        if (auto found = faces_.find({path, index}); found != faces_.end()) return found->second;
        FT_Face ft = nullptr;
        if (FT_New_Face(freetype(shown_), path.c_str(), index, &ft) != 0) fail(shown_, "cannot load font " + path);
        cairo_font_face_t* face = cairo_ft_font_face_create_for_ft_face(ft, 0);
        static const cairo_user_data_key_t key{};
        if (cairo_font_face_set_user_data(face, &key, ft, [](void* f) { FT_Done_Face(static_cast<FT_Face>(f)); }) !=
            CAIRO_STATUS_SUCCESS) {
            cairo_font_face_destroy(face);
            FT_Done_Face(ft);
            fail(shown_, "cairo cannot keep font " + path);
        }
        faces_.emplace(std::make_pair(path, index), face);
        return face;
    }

private:
    const std::string& shown_;
    std::map<std::pair<std::string, int>, cairo_font_face_t*> faces_;
};

// What painting a page needs besides the item.
struct Context {
    Fonts fonts;
    int format;
    std::vector<bool> nearest;  // per picture painted: whether it is nearest-sampled (mark_nearest)
};

void set_colour(cairo_t* cr, const float c[4]) { cairo_set_source_rgba(cr, c[0], c[1], c[2], c[3]); }

void add_path(cairo_t* cr, const figgen_vector_item& item) {
    for (std::size_t k = 0; k < item.path_steps; ++k) {
        const figgen_path_step& step = item.path[k];
        switch (step.kind) {
            case FIGGEN_PATH_MOVE: cairo_move_to(cr, step.x, step.y); break;
            case FIGGEN_PATH_LINE: cairo_line_to(cr, step.x, step.y); break;
            case FIGGEN_PATH_CLOSE: cairo_close_path(cr); break;
            case FIGGEN_PATH_CIRCLE:
                // Counter-clockwise on screen is decreasing angle in y-down space: every
                // circle winds the way the page's polygons are made to wind.
                cairo_new_sub_path(cr);
                cairo_arc_negative(cr, step.x, step.y, step.radius, 0, -2 * std::numbers::pi);
                cairo_close_path(cr);
                break;
            default: throw std::invalid_argument("a path step of unknown kind " + std::to_string(step.kind));
        }
    }
}

void fill(cairo_t* cr, const figgen_vector_item& f) {
    add_path(cr, f);
    set_colour(cr, f.colour);
    cairo_set_fill_rule(cr, f.even_odd ? CAIRO_FILL_RULE_EVEN_ODD : CAIRO_FILL_RULE_WINDING);
    cairo_fill(cr);
}

void stroke(cairo_t* cr, const figgen_vector_item& s) {
    add_path(cr, s);
    set_colour(cr, s.colour);
    cairo_set_line_width(cr, s.width);
    cairo_set_line_cap(cr, s.cap == FIGGEN_CAP_ROUND    ? CAIRO_LINE_CAP_ROUND
                           : s.cap == FIGGEN_CAP_SQUARE ? CAIRO_LINE_CAP_SQUARE
                                                        : CAIRO_LINE_CAP_BUTT);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    std::vector<double> dash(s.dash, s.dash + s.dash_count);
    cairo_set_dash(cr, dash.data(), static_cast<int>(dash.size()), s.dash_offset);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
}

void glyphs(cairo_t* cr, const figgen_vector_item& g, Context& c) {
    cairo_save(cr);
    cairo_set_font_face(cr, c.fonts.face(g.font_path ? g.font_path : "", g.font_index));
    cairo_set_font_size(cr, g.pixel_size);
    cairo_translate(cr, g.origin[0], g.origin[1]);
    cairo_rotate(cr, -g.rotation_degrees * std::numbers::pi / 180);
    std::vector<cairo_glyph_t> glyphs;
    glyphs.reserve(g.glyph_count);
    for (std::size_t k = 0; k < g.glyph_count; ++k) glyphs.push_back({g.glyphs[k].index, g.glyphs[k].x, g.glyphs[k].y});
    set_colour(cr, g.colour);
    // With the text and each glyph's cluster, a PDF's text can be searched and copied.
    std::vector<cairo_text_cluster_t> clusters;
    std::size_t bytes = 0, clustered = 0;
    for (std::size_t k = 0; k < g.cluster_count; ++k) {
        const figgen_cluster& cluster = g.clusters[k];
        clusters.push_back({cluster.bytes, cluster.glyphs});
        bytes += static_cast<std::size_t>(std::max(cluster.bytes, 0));
        clustered += static_cast<std::size_t>(std::max(cluster.glyphs, 0));
    }
    if (g.text_bytes > 0 && bytes == g.text_bytes && clustered == glyphs.size())
        cairo_show_text_glyphs(cr, g.text, static_cast<int>(g.text_bytes), glyphs.data(),
                               static_cast<int>(glyphs.size()), clusters.data(), static_cast<int>(clusters.size()),
                               g.backward ? CAIRO_TEXT_CLUSTER_FLAG_BACKWARD : cairo_text_cluster_flags_t(0));
    else
        cairo_show_glyphs(cr, glyphs.data(), static_cast<int>(glyphs.size()));
    cairo_restore(cr);
}

void picture(cairo_t* cr, const figgen_vector_item& p, Context& c) {
    const float x = p.box[0], y = p.box[1], w = p.box[2], h = p.box[3];
    if (p.image_width < 1 || p.image_height < 1 || !p.pixels || !(w > 0) || !(h > 0)) return;
    c.nearest.push_back(!p.smooth);
    // In SVG a nearest image is enlarged by whole pixels to about its
    // rectangle's size: librsvg, among other viewers, ignores image-rendering
    // and would blur each cell into its neighbours; enlarged, only the cells'
    // edges can soften. PDF keeps the cells, with /Interpolate false.
    int kx = 1, ky = 1;
    if (!p.smooth && c.format == FIGGEN_VECTOR_SVG) {
        kx = std::max(1, static_cast<int>(std::ceil(w / float(p.image_width) - 1e-3f)));
        ky = std::max(1, static_cast<int>(std::ceil(h / float(p.image_height) - 1e-3f)));
    }
    const int width = p.image_width * kx, height = p.image_height * ky;
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
    cairo_surface_flush(surface);
    unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    for (int row_y = 0; row_y < height; ++row_y) {
        auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(row_y) * stride);
        for (int col = 0; col < width; ++col) {
            const std::uint8_t* px =
                p.pixels + (static_cast<std::size_t>(row_y / ky) * static_cast<std::size_t>(p.image_width) +
                            static_cast<std::size_t>(col / kx)) * 4;
            const unsigned a = px[3];
            auto pre = [a](unsigned v) { return (v * a + 127) / 255; };
            // ARGB32: premultiplied, in a native-endian 32-bit word.
            row[col] = (a << 24) | (pre(px[0]) << 16) | (pre(px[1]) << 8) | pre(px[2]);
        }
    }
    cairo_surface_mark_dirty(surface);
    cairo_save(cr);
    cairo_rectangle(cr, x, y, w, h);
    cairo_clip(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, w / width, h / height);
    cairo_set_source_surface(cr, surface, 0, 0);
    cairo_pattern_t* pattern = cairo_get_source(cr);
    cairo_pattern_set_extend(pattern, CAIRO_EXTEND_PAD);
    cairo_pattern_set_filter(pattern, p.smooth ? CAIRO_FILTER_GOOD : CAIRO_FILTER_NEAREST);
    cairo_paint(cr);
    cairo_restore(cr);
    cairo_surface_destroy(surface);
}

void draw(cairo_t* cr, const figgen_vector_item& item, Context& c) {
    switch (item.kind) {
        case FIGGEN_ITEM_FILL: return fill(cr, item);
        case FIGGEN_ITEM_STROKE: return stroke(cr, item);
        case FIGGEN_ITEM_GLYPHS: return glyphs(cr, item, c);
        case FIGGEN_ITEM_PICTURE: return picture(cr, item, c);
        case FIGGEN_ITEM_CLIP:
            cairo_save(cr);
            cairo_rectangle(cr, item.box[0], item.box[1], item.box[2] - item.box[0], item.box[3] - item.box[1]);
            cairo_clip(cr);
            return;
        case FIGGEN_ITEM_UNCLIP: cairo_restore(cr); return;
        case FIGGEN_ITEM_GROUP_BEGIN: cairo_push_group(cr); return;
        case FIGGEN_ITEM_GROUP_END:
            cairo_pop_group_to_source(cr);
            cairo_paint_with_alpha(cr, item.alpha);
            return;
        default: throw std::invalid_argument("an item of unknown kind " + std::to_string(item.kind));
    }
}

void write(int fd, const std::string& shown, int format, const figgen_vector_page& page, std::uint64_t max_bytes) {
    if (page.width < 1 || page.height < 1) fail(shown, "the page is empty");
    if (format != FIGGEN_VECTOR_PDF && format != FIGGEN_VECTOR_SVG) fail(shown, "an unknown format");
    Sink sink{fd, max_bytes};
    std::string svg;
    cairo_surface_t* surface = nullptr;
    double unit = 1;  // page units a pixel
    if (format == FIGGEN_VECTOR_PDF) {
        unit = 72.0 / 100.0;  // the PNG's pixels at 100 dpi
        surface = cairo_pdf_surface_create_for_stream(write_to_fd, &sink, page.width * unit, page.height * unit);
        cairo_pdf_surface_restrict_to_version(surface, CAIRO_PDF_VERSION_1_5);
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, page.title ? page.title : "");
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, page.creator ? page.creator : "");
        // No creation date: the same figure gives the same bytes.
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATE_DATE, "");
    } else {
        sink.held = &svg;
        surface = cairo_svg_surface_create_for_stream(write_to_fd, &sink, page.width, page.height);
        cairo_svg_surface_restrict_to_version(surface, CAIRO_SVG_VERSION_1_1);
        cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_PX);
    }
    std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> owned_surface(surface, cairo_surface_destroy);
    check(cairo_surface_status(surface), sink, shown);
    std::vector<bool> nearest;
    {
        Context context{Fonts(shown), format, {}};
        cairo_t* cr = cairo_create(surface);
        std::unique_ptr<cairo_t, void (*)(cairo_t*)> owned_cr(cr, cairo_destroy);
        cairo_scale(cr, unit, unit);
        cairo_font_options_t* options = cairo_font_options_create();
        cairo_font_options_set_hint_style(options, CAIRO_HINT_STYLE_NONE);
        cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
        cairo_set_font_options(cr, options);
        cairo_font_options_destroy(options);
        for (std::size_t k = 0; k < page.item_count; ++k) {
            figgen_vector_item item{};
            if (page.item(page.items, k, &item) != 0) fail(shown, "the page has no item " + std::to_string(k));
            draw(cr, item, context);
        }
        check(cairo_status(cr), sink, shown);
        nearest = std::move(context.nearest);
        owned_cr.reset();
    }
    cairo_surface_finish(surface);
    check(cairo_surface_status(surface), sink, shown);
    // cairo 1.16's PDF surface does not always carry a failed write into its
    // status: what the sink saw decides too.
    if (sink.too_large || sink.error != 0) check(CAIRO_STATUS_WRITE_ERROR, sink, shown);
    if (format == FIGGEN_VECTOR_SVG) {
        mark_nearest(svg, nearest);
        if (svg.size() > max_bytes) {
            sink.too_large = true;
            check(CAIRO_STATUS_WRITE_ERROR, sink, shown);
        }
        if (!write_all(sink, reinterpret_cast<const unsigned char*>(svg.data()), svg.size()))
            check(CAIRO_STATUS_WRITE_ERROR, sink, shown);
    }
}

// The C entry: nothing thrown crosses it.
int write_c(int fd, const char* shown, int32_t format, const figgen_vector_page* page, uint64_t max_bytes,
            char* error, size_t error_size) {
    const std::string path = shown ? shown : "the vector file";
    try {
        if (!page) fail(path, "no page");
        write(fd, path, format, *page, max_bytes);
        return 0;
    } catch (const std::exception& e) {
        if (error && error_size > 0) std::snprintf(error, error_size, "%s", e.what());
    } catch (...) {
        if (error && error_size > 0) std::snprintf(error, error_size, "cannot write %s", path.c_str());
    }
    return 1;
}

const figgen_vector_api functions{FIGGEN_VECTOR_ABI_VERSION, write_c};

}  // namespace

extern "C" const figgen_vector_api* figgen_vector_module(void) {
    return &functions;
}
