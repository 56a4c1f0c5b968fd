#include "render/colormap.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace render {
namespace {

const std::array<Colormap, 4>& all() {
    static const std::array<Colormap, 4> maps{{
        {"Reds", tables::Reds},
        {"Blues", tables::Blues},
        {"Greens", tables::Greens},
        {"viridis", tables::viridis},
    }};
    return maps;
}

}  // namespace

glm::vec3 Colormap::at(double t) const {
    // matplotlib: xa = int(t * N), then t == 1 lands on N - 1, and out of range clips.
    const double scaled = std::floor(t * size);
    const int i = scaled < 0 ? 0 : scaled >= size ? size - 1 : static_cast<int>(scaled);
    return {table[i][0], table[i][1], table[i][2]};
}

const Colormap& colormap(std::string_view name) {
    for (const Colormap& map : all())
        if (map.name == name) return map;
    std::string allowed;
    for (const Colormap& map : all()) allowed += (allowed.empty() ? "" : ", ") + map.name;
    throw std::invalid_argument("colormap \"" + std::string(name) + "\" is unknown: allowed are " + allowed);
}

std::vector<std::string> colormap_names() {
    std::vector<std::string> names;
    for (const Colormap& map : all()) names.push_back(map.name);
    return names;
}

}  // namespace render
