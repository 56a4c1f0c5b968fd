#pragma once
// Colormaps as matplotlib defines them: a lookup table of N entries (256 for
// the named maps), and a value v in [vmin, vmax] picks entry
// floor((v - vmin) / (vmax - vmin) * N), clipped to 0..N-1, as matplotlib's
// Colormap.__call__ does.

#include <array>
#include <optional>
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
extern const float inferno[256][3];
extern const float magma[256][3];
extern const float plasma[256][3];
extern const float cividis[256][3];
}  // namespace tables

struct Colormap {
    std::string name;                // matplotlib's name, e.g. "Reds"
    std::vector<glm::vec3> colours;  // N entries, RGB 0..1: 256 for the built-in maps

    // The colour of value v normalised to [0, 1] (t = (v - vmin) / (vmax - vmin)):
    // entry floor(t * N), clipped to 0..N-1, as matplotlib picks it.
    glm::vec3 at(double t) const;
    int size() const { return static_cast<int>(colours.size()); }
};

// The built-in colormap called `name`; throws std::invalid_argument listing the names allowed.
const Colormap& colormap(std::string_view name);
// The same, or null for an unknown name.
const Colormap* find_colormap(std::string_view name);
std::vector<std::string> colormap_names();

// matplotlib's ListedColormap: N colours, t picks colour floor(t * N) (clipped).
// With vmin 0 and vmax N-1, the integer states 0..N-1 get colours 0..N-1.
Colormap listed_colormap(std::string name, const std::vector<glm::vec3>& colours);

// "#rrggbb" or a few of matplotlib's named colours (white, black, green,
// orange, ...); throws std::invalid_argument naming what is allowed.
glm::vec3 parse_colour(std::string_view text);
// The same, or nothing for a text that names no colour.
std::optional<glm::vec3> find_colour(std::string_view text);
// What parse_colour accepts, for messages: "#rrggbb or one of white, black, ...".
std::string colours_allowed();

}  // namespace render
