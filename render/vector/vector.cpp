#include "render/vector/vector.hpp"

#include <stdexcept>
#include <type_traits>

#include "base/module.hpp"
#include "render/vector/vector_abi.h"

namespace render::vector {
namespace {

constexpr base::ModuleSpec spec{FIGGEN_VECTOR_RELATIVE,
                                FIGGEN_VECTOR_BUILT,
                                "figgen_vector_module",
                                FIGGEN_VECTOR_ABI_VERSION,
                                "vector module for PDF and SVG",
                                "libcairo2"};

base::LoadedModule<figgen_vector_api>& module() {
    return base::module_of<figgen_vector_api, spec>();
}

// The page as the module reads it, and the item being handed over: its
// path, glyphs and clusters in C types, for one item at a time.
struct Handover {
    const Page* page;
    std::vector<figgen_path_step> path;
    std::vector<figgen_glyph> glyphs;
    std::vector<figgen_cluster> clusters;
};

void set_colour(float out[4], const glm::vec4& c) {
    out[0] = c.r, out[1] = c.g, out[2] = c.b, out[3] = c.a;
}

void set_path(figgen_vector_item& item, const Path& path, std::vector<figgen_path_step>& steps) {
    steps.clear();
    steps.reserve(path.size());
    for (const PathStep& s : path) {
        const int kind = s.kind == PathStep::move    ? FIGGEN_PATH_MOVE
                         : s.kind == PathStep::line  ? FIGGEN_PATH_LINE
                         : s.kind == PathStep::close ? FIGGEN_PATH_CLOSE
                                                     : FIGGEN_PATH_CIRCLE;
        steps.push_back({kind, s.at.x, s.at.y, s.radius});
    }
    item.path = steps.data();
    item.path_steps = steps.size();
}

int item_at(void* items, std::size_t index, figgen_vector_item* out) {
    auto& h = *static_cast<Handover*>(items);
    if (index >= h.page->items.size()) return 1;
    figgen_vector_item item{};
    std::visit(
        [&](const auto& i) {
            using T = std::decay_t<decltype(i)>;
            if constexpr (std::is_same_v<T, Fill>) {
                item.kind = FIGGEN_ITEM_FILL;
                set_path(item, i.path, h.path);
                set_colour(item.colour, i.colour);
                item.even_odd = i.rule == FillRule::even_odd;
            } else if constexpr (std::is_same_v<T, Stroke>) {
                item.kind = FIGGEN_ITEM_STROKE;
                set_path(item, i.path, h.path);
                set_colour(item.colour, i.colour);
                item.width = i.width;
                item.cap = i.cap == Cap::round    ? FIGGEN_CAP_ROUND
                           : i.cap == Cap::square ? FIGGEN_CAP_SQUARE
                                                  : FIGGEN_CAP_BUTT;
                item.dash = i.dash.data();
                item.dash_count = i.dash.size();
                item.dash_offset = i.dash_offset;
            } else if constexpr (std::is_same_v<T, Glyphs>) {
                item.kind = FIGGEN_ITEM_GLYPHS;
                set_colour(item.colour, i.colour);
                item.font_path = i.font_path.c_str();
                item.font_index = i.font_index;
                item.pixel_size = i.pixel_size;
                item.origin[0] = i.origin.x, item.origin[1] = i.origin.y;
                item.rotation_degrees = i.rotation_degrees;
                h.glyphs.clear();
                for (const Glyphs::Glyph& g : i.glyphs) h.glyphs.push_back({g.index, g.position.x, g.position.y});
                item.glyphs = h.glyphs.data();
                item.glyph_count = h.glyphs.size();
                item.text = i.text.data();
                item.text_bytes = i.text.size();
                h.clusters.clear();
                for (const auto& [bytes, glyphs] : i.clusters) h.clusters.push_back({bytes, glyphs});
                item.clusters = h.clusters.data();
                item.cluster_count = h.clusters.size();
                item.backward = i.backward;
            } else if constexpr (std::is_same_v<T, Picture>) {
                item.kind = FIGGEN_ITEM_PICTURE;
                item.pixels = i.image.rgba.data();
                item.image_width = i.image.width;
                item.image_height = i.image.height;
                item.box[0] = i.where.x, item.box[1] = i.where.y, item.box[2] = i.where.w, item.box[3] = i.where.h;
                item.smooth = i.smooth;
            } else if constexpr (std::is_same_v<T, Clip>) {
                item.kind = FIGGEN_ITEM_CLIP;
                item.box[0] = static_cast<float>(i.box.x0), item.box[1] = static_cast<float>(i.box.y0);
                item.box[2] = static_cast<float>(i.box.x1), item.box[3] = static_cast<float>(i.box.y1);
            } else if constexpr (std::is_same_v<T, Unclip>) {
                item.kind = FIGGEN_ITEM_UNCLIP;
            } else if constexpr (std::is_same_v<T, GroupBegin>) {
                item.kind = FIGGEN_ITEM_GROUP_BEGIN;
            } else {
                static_assert(std::is_same_v<T, GroupEnd>);
                item.kind = FIGGEN_ITEM_GROUP_END;
                item.alpha = i.alpha;
            }
        },
        h.page->items[index]);
    *out = item;
    return 0;
}

}  // namespace

void write(int fd, const std::filesystem::path& shown, Format format, const Page& page, std::uint64_t max_bytes) {
    const figgen_vector_api& api = module().api();
    Handover handover{&page, {}, {}, {}};
    const figgen_vector_page c{page.width,          page.height, page.title.c_str(), page.creator.c_str(),
                               page.items.size(), item_at,     &handover};
    char error[1024] = "";
    const std::string path = shown.string();
    if (api.write(fd, path.c_str(), static_cast<int>(format), &c, max_bytes,
                  error, sizeof error) != 0)
        throw std::runtime_error(error[0] ? error : "cannot write " + path);
}

void preload() {
    module().preload();
}

}  // namespace render::vector
