#pragma once
// The surface where a 3-D field crosses a level, as lit facets with smooth
// normals, for draw_tubes (render/tubes.hpp): marching cubes. A cube of
// eight neighbouring samples whose corners lie on both sides of the level
// holds up to twelve triangles, their corners where the field, interpolated
// linearly along the cube's edges, equals the level. The triangles of each
// of the 256 cases are made from the cube's faces, each face cut the same
// way from both cubes that share it (its corners above the level kept
// apart), so the surface has no cracks. A corner's normal is the field's
// gradient there (central differences, one-sided at the grid's faces),
// interpolated the same way and pointing out of the region above the level;
// each triangle is wound so that its front faces the same way. Capped, the
// region above the level is closed where it meets the grid's faces.

#include <algorithm>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/tubes.hpp"

namespace render {

struct IsosurfaceGrid {
    int nx = 0, ny = 0, nz = 0;       // cells along x, y, z
    std::span<const double> values;   // nx * ny * nz, x fastest, then y, then z
    // Closed by flat caps where the region above the level meets the
    // grid's faces (Ready's cap_contour); open there when false.
    bool capped = true;
    // The region the surface closes: the values above the level, or
    // below it (Ready's invert_contour_cap); its normals point out of it.
    bool inside_below = false;
};

// How many facets a surface drawn into `pixels` pixels needs at most: two
// a pixel (and never fewer than 20,000). A finer one shows nothing more,
// and llvmpipe's time grows with the facets it draws.
constexpr long long facets_for_pixels(long long pixels) { return std::max(2 * pixels, 20'000LL); }

// The facets of the level surface in world coordinates: the cell (x, y, z)
// at world (x, y, z) * spacing. Sampled every `stride` cells along each
// axis (1: every cell). Throws std::invalid_argument for a grid whose
// values do not match its size or a level that is not finite.
std::vector<Facet> isosurface(const IsosurfaceGrid& grid, double level, const glm::vec4& colour, int stride = 1);

// The least stride (1, 2, 3, ...) at which the surface has at most
// `most_facets` facets, and those facets: a grid too fine for the budget is
// sampled more coarsely, the same way every time. The facets of a stride are
// counted before any is made.
std::vector<Facet> isosurface_within(const IsosurfaceGrid& grid, double level, const glm::vec4& colour,
                                     long long most_facets, int* stride_used = nullptr);

}  // namespace render
