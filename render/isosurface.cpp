#include "render/isosurface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace render {
namespace {

// The corners of a cube: corner k is at (k & 1, k >> 1 & 1, k >> 2 & 1).
// Its six tetrahedra about the diagonal from corner 0 to corner 7.
constexpr int tetrahedra[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};

struct Sampled {
    const IsosurfaceGrid& grid;
    int stride;
    int sx, sy, sz;  // sample points along each axis

    // The sample point (i, j, k): the cell at stride times it, the last
    // sample on the grid's far face.
    int cell(int i, int samples, int n) const { return i == samples - 1 ? n - 1 : i * stride; }
    double value_at(int x, int y, int z) const {
        return grid.values[(static_cast<std::size_t>(z) * grid.ny + y) * grid.nx + x];
    }
    // The field's gradient at a cell, as a normal pointing down it (out of the region above the level).
    glm::vec3 normal_at(int x, int y, int z) const {
        auto d = [&](int axis) {
            int lo[3] = {x, y, z}, hi[3] = {x, y, z};
            const int n[3] = {grid.nx, grid.ny, grid.nz};
            lo[axis] = std::max(0, lo[axis] - 1);
            hi[axis] = std::min(n[axis] - 1, hi[axis] + 1);
            if (hi[axis] == lo[axis]) return 0.0;
            return (value_at(hi[0], hi[1], hi[2]) - value_at(lo[0], lo[1], lo[2])) / (hi[axis] - lo[axis]);
        };
        return -glm::vec3(float(d(0)), float(d(1)), float(d(2)));
    }
};

struct Corner {
    glm::vec3 position, normal;
    double value;
};

// Walks the sampled cubes; emit(a, b, c) gets each triangle's corners
// (position, normal), wound to face along the normals.
template <class Emit>
void march(const Sampled& s, double level, Emit&& emit) {
    struct Point {
        glm::vec3 position, normal;
    };
    // Always from the corner above the level to the one below: the tetrahedra
    // that share an edge put its point at the same bits (no cracks).
    auto cut = [&](const Corner& p, const Corner& q) {
        const Corner& a = p.value > level ? p : q;
        const Corner& b = p.value > level ? q : p;
        const double t = (level - a.value) / (b.value - a.value);
        const float f = static_cast<float>(std::clamp(t, 0.0, 1.0));
        return Point{a.position + f * (b.position - a.position), a.normal + f * (b.normal - a.normal)};
    };
    auto triangle = [&](const Point& a, const Point& b, const Point& c) {
        const glm::vec3 across = glm::cross(b.position - a.position, c.position - a.position);
        if (glm::dot(across, a.normal + b.normal + c.normal) < 0) emit(a.position, a.normal, c.position, c.normal, b.position, b.normal);
        else emit(a.position, a.normal, b.position, b.normal, c.position, c.normal);
    };
    std::array<Corner, 8> corner;
    for (int k = 0; k + 1 < s.sz; ++k)
        for (int j = 0; j + 1 < s.sy; ++j)
            for (int i = 0; i + 1 < s.sx; ++i) {
                int above = 0;
                for (int c = 0; c < 8; ++c) {
                    const int x = s.cell(i + (c & 1), s.sx, s.grid.nx), y = s.cell(j + (c >> 1 & 1), s.sy, s.grid.ny),
                              z = s.cell(k + (c >> 2 & 1), s.sz, s.grid.nz);
                    corner[c].value = s.value_at(x, y, z);
                    above += corner[c].value > level;
                }
                if (above == 0 || above == 8) continue;
                for (int c = 0; c < 8; ++c) {
                    const int x = s.cell(i + (c & 1), s.sx, s.grid.nx), y = s.cell(j + (c >> 1 & 1), s.sy, s.grid.ny),
                              z = s.cell(k + (c >> 2 & 1), s.sz, s.grid.nz);
                    corner[c].position = glm::vec3(float(x), float(y), float(z));
                    corner[c].normal = s.normal_at(x, y, z);
                }
                for (const auto& t : tetrahedra) {
                    int in[4], out[4], n_in = 0, n_out = 0;
                    for (int v : t) (corner[v].value > level ? in[n_in++] : out[n_out++]) = v;
                    if (n_in == 0 || n_out == 0) continue;
                    if (n_in == 1 || n_out == 1) {
                        // One corner apart from the other three: a triangle across its three edges.
                        const int lone = n_in == 1 ? in[0] : out[0];
                        const int* rest = n_in == 1 ? out : in;
                        triangle(cut(corner[lone], corner[rest[0]]), cut(corner[lone], corner[rest[1]]),
                                 cut(corner[lone], corner[rest[2]]));
                    } else {
                        // Two and two: a quad across four edges, as two triangles.
                        const Point p = cut(corner[in[0]], corner[out[0]]), q = cut(corner[in[0]], corner[out[1]]),
                                    r = cut(corner[in[1]], corner[out[1]]), u = cut(corner[in[1]], corner[out[0]]);
                        triangle(p, q, r);
                        triangle(p, r, u);
                    }
                }
            }
}

Sampled sampled(const IsosurfaceGrid& grid, double level, int stride) {
    if (grid.nx < 1 || grid.ny < 1 || grid.nz < 1 ||
        grid.values.size() != static_cast<std::size_t>(grid.nx) * grid.ny * grid.nz)
        throw std::invalid_argument("isosurface: the grid's values do not fill " + std::to_string(grid.nx) + " x " +
                                    std::to_string(grid.ny) + " x " + std::to_string(grid.nz));
    if (!std::isfinite(level)) throw std::invalid_argument("isosurface: the level is not a finite number");
    if (stride < 1) throw std::invalid_argument("isosurface: the stride is below 1");
    auto samples = [&](int n) { return n == 1 ? 1 : (n - 1 + stride - 1) / stride + 1; };
    return {grid, stride, samples(grid.nx), samples(grid.ny), samples(grid.nz)};
}

}  // namespace

std::vector<Facet> isosurface(const IsosurfaceGrid& grid, double level, const glm::vec4& colour, int stride) {
    const Sampled s = sampled(grid, level, stride);
    std::vector<Facet> facets;
    march(s, level, [&](glm::vec3 a, glm::vec3 na, glm::vec3 b, glm::vec3 nb, glm::vec3 c, glm::vec3 nc) {
        facets.push_back({a, b, c, colour, na, nb, nc});
    });
    return facets;
}

std::vector<Facet> isosurface_within(const IsosurfaceGrid& grid, double level, const glm::vec4& colour,
                                     long long most_facets, int* stride_used) {
    for (int stride = 1;; ++stride) {
        long long count = 0;
        march(sampled(grid, level, stride), level, [&](auto&&...) { ++count; });
        if (count <= most_facets || stride >= std::max({grid.nx, grid.ny, grid.nz})) {
            if (stride_used) *stride_used = stride;
            return isosurface(grid, level, colour, stride);
        }
    }
}

}  // namespace render
