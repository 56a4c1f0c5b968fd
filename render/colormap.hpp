#pragma once
// Colormaps as matplotlib defines them: a 256-entry lookup table, and a value
// v in [vmin, vmax] picks entry floor((v - vmin) / (vmax - vmin) * 256),
// clipped to 0..255, as matplotlib's Colormap.__call__ does.

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace render {

namespace tables {
extern const float Reds[256][3];
extern const float Blues[256][3];
extern const float Greens[256][3];
extern const float viridis[256][3];
}  // namespace tables

struct Colormap {
    std::string name;                   // matplotlib's name, e.g. "Reds"
    const float (*table)[3] = nullptr;  // 256 RGB entries, 0..1

    static constexpr int size = 256;
    // The colour of value v normalised to [0, 1] (t = (v - vmin) / (vmax - vmin)).
    glm::vec3 at(double t) const;
};

// The colormap called `name`; throws std::invalid_argument listing the names allowed.
const Colormap& colormap(std::string_view name);
std::vector<std::string> colormap_names();

}  // namespace render
