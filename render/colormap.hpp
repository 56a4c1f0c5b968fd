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
    static constexpr int size = 256;
    std::string name;                      // matplotlib's name, e.g. "Reds"
    std::array<glm::vec3, size> colours;   // RGB, 0..1

    // The colour of value v normalised to [0, 1] (t = (v - vmin) / (vmax - vmin)).
    glm::vec3 at(double t) const;
};

// The built-in colormap called `name`; throws std::invalid_argument listing the names allowed.
const Colormap& colormap(std::string_view name);
std::vector<std::string> colormap_names();

// matplotlib's ListedColormap: N colours, t picks colour floor(t * N) (clipped).
// With vmin 0 and vmax N-1, the integer states 0..N-1 get colours 0..N-1.
Colormap listed_colormap(std::string name, const std::vector<glm::vec3>& colours);

// "#rrggbb" or a few of matplotlib's named colours (white, black, green,
// orange, ...); throws std::invalid_argument naming what is allowed.
glm::vec3 parse_colour(std::string_view text);

}  // namespace render
