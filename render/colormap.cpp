#include "render/colormap.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace render {
namespace {

Colormap from_table(std::string name, const float (*table)[3]) {
    Colormap map{std::move(name), std::vector<glm::vec3>(256)};
    for (int i = 0; i < 256; ++i) map.colours[i] = {table[i][0], table[i][1], table[i][2]};
    return map;
}

const std::vector<Colormap>& builtins() {
    static const std::vector<Colormap> maps = {
        from_table("Reds", tables::Reds),
        from_table("Blues", tables::Blues),
        from_table("Greens", tables::Greens),
        from_table("viridis", tables::viridis),
        from_table("inferno", tables::inferno),
        from_table("magma", tables::magma),
        from_table("plasma", tables::plasma),
        from_table("cividis", tables::cividis),
    };
    return maps;
}

// matplotlib's CSS4 values for the names figures use.
struct NamedColour {
    const char* name;
    glm::vec3 rgb;
};
constexpr NamedColour named_colours[] = {
    {"white", {1, 1, 1}},
    {"black", {0, 0, 0}},
    {"green", {0, 128 / 255.0f, 0}},
    {"orange", {1, 165 / 255.0f, 0}},
    {"red", {1, 0, 0}},
    {"blue", {0, 0, 1}},
    {"gray", {128 / 255.0f, 128 / 255.0f, 128 / 255.0f}},
};

}  // namespace

glm::vec3 Colormap::at(double t) const {
    // matplotlib: xa = int(t * N), then t == 1 lands on N - 1, and out of range clips.
    const int n = size();
    const double scaled = std::floor(t * n);
    const int i = scaled < 0 ? 0 : scaled >= n ? n - 1 : static_cast<int>(scaled);
    return colours[i];
}

const Colormap* find_colormap(std::string_view name) {
    for (const Colormap& map : builtins())
        if (map.name == name) return &map;
    return nullptr;
}

const Colormap& colormap(std::string_view name) {
    if (const Colormap* map = find_colormap(name)) return *map;
    std::string allowed;
    for (const Colormap& map : builtins()) allowed += (allowed.empty() ? "" : ", ") + map.name;
    throw std::invalid_argument("colormap \"" + std::string(name) + "\" is unknown: allowed are " + allowed);
}

std::vector<std::string> colormap_names() {
    std::vector<std::string> names;
    for (const Colormap& map : builtins()) names.push_back(map.name);
    return names;
}

Colormap listed_colormap(std::string name, const std::vector<glm::vec3>& colours) {
    if (colours.empty() || colours.size() > 4096)
        throw std::invalid_argument("a listed colormap needs 1 to 4096 colours");
    return {std::move(name), colours};
}

glm::vec3 parse_colour(std::string_view text) {
    if (const auto colour = find_colour(text)) return *colour;
    throw std::invalid_argument("colour \"" + std::string(text) + "\" is not allowed: use " + colours_allowed());
}

std::string colours_allowed() {
    std::string names;
    for (const NamedColour& c : named_colours) names += std::string(names.empty() ? "" : ", ") + c.name;
    return "#rrggbb or one of " + names;
}

std::optional<glm::vec3> find_colour(std::string_view text) {
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    if (text.size() == 7 && text[0] == '#') {
        int v[6];
        for (int i = 0; i < 6; ++i) v[i] = hex(text[i + 1]);
        if (std::all_of(v, v + 6, [](int x) { return x >= 0; }))
            return glm::vec3(v[0] * 16 + v[1], v[2] * 16 + v[3], v[4] * 16 + v[5]) / 255.0f;
    }
    for (const NamedColour& c : named_colours)
        if (text == c.name) return c.rgb;
    return std::nullopt;
}

}  // namespace render
