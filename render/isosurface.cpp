#include "render/isosurface.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
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
    bool capped;     // a sample beyond each face, below the level
    double sign;     // 1, or -1 when the region inside is below the level: the walk sees sign * value

    // The sample point (i, j, k): the cell at stride times it, the last
    // sample on the grid's far face.
    int cell(int i, int samples, int n) const { return i >= samples - 1 ? n - 1 : i <= 0 ? 0 : i * stride; }
    double value_at(int x, int y, int z) const {
        return sign * grid.values[(static_cast<std::size_t>(z) * grid.ny + y) * grid.nx + x];
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
    bool beyond = false;  // a sample past a face of the grid (capping): below the level, its normal facing out
};

// Walks the sampled cubes; emit(a, na, b, nb, c, nc) gets each triangle's
// corners and normals, wound to face along the normals, and says whether
// to go on (false: stop the walk). Capped, the walk
// goes one sample past each face: a sample there is below the level and
// its normal faces out; an edge from a corner on the face to it is cut at
// that corner, so the region above the level is closed by flat caps on the
// grid's faces.
// Which samples lie above the level (those past a face never): a cube
// whose eight agree is passed over at the cost of eight bytes. Indexed
// from -1 on each axis.
std::vector<std::uint8_t> above_level(const Sampled& s, double level) {
    const int px = s.sx + 2, py = s.sy + 2, pz = s.sz + 2;
    std::vector<std::uint8_t> up(static_cast<std::size_t>(px) * py * pz, 0);
#pragma omp parallel for schedule(static)
    for (int k = 0; k < s.sz; ++k)
        for (int j = 0; j < s.sy; ++j)
            for (int i = 0; i < s.sx; ++i)
                up[(static_cast<std::size_t>(k + 1) * py + (j + 1)) * px + (i + 1)] =
                    s.value_at(s.cell(i, s.sx, s.grid.nx), s.cell(j, s.sy, s.grid.ny), s.cell(k, s.sz, s.grid.nz)) > level;
    return up;
}

// The layers of cubes the walk goes through: k from first_layer to
// last_layer - 1 (one more on each side, capped).
int first_layer(const Sampled& s) { return s.capped ? -1 : 0; }
int last_layer(const Sampled& s) { return s.sz - 1 + (s.capped ? 1 : 0); }

// Walks the cubes of layers k_from .. k_to - 1, in order.
template <class Emit>
void march(const Sampled& s, double level, const std::vector<std::uint8_t>& up, int k_from, int k_to, Emit&& emit) {
    struct Point {
        glm::vec3 position, normal;
    };
    // Always from the corner above the level to the one below: the tetrahedra
    // that share an edge put its point at the same bits (no cracks).
    auto cut = [&](const Corner& p, const Corner& q) {
        const Corner& a = p.value > level ? p : q;
        const Corner& b = p.value > level ? q : p;
        // Past a face: the cap's corner is the inside corner itself, which lies on the face.
        if (b.beyond) return Point{a.position, b.normal};
        const double t = (level - a.value) / (b.value - a.value);
        const float f = static_cast<float>(std::clamp(t, 0.0, 1.0));
        return Point{a.position + f * (b.position - a.position), a.normal + f * (b.normal - a.normal)};
    };
    bool going = true;
    auto triangle = [&](const Point& a, const Point& b, const Point& c) {
        const glm::vec3 across = glm::cross(b.position - a.position, c.position - a.position);
        if (glm::dot(across, a.normal + b.normal + c.normal) < 0)
            going = emit(a.position, a.normal, c.position, c.normal, b.position, b.normal) && going;
        else
            going = emit(a.position, a.normal, b.position, b.normal, c.position, c.normal) && going;
    };
    const int first = first_layer(s);
    const int px = s.sx + 2, py = s.sy + 2;
    auto up_at = [&](int i, int j, int k) { return up[(static_cast<std::size_t>(k + 1) * py + (j + 1)) * px + (i + 1)]; };
    std::array<Corner, 8> corner;
    for (int k = k_from; k < k_to; ++k)
        for (int j = first; j + 1 < s.sy + (s.capped ? 1 : 0); ++j)
            for (int i = first; i + 1 < s.sx + (s.capped ? 1 : 0); ++i) {
                int quick = 0;
                for (int c = 0; c < 8; ++c) quick += up_at(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1));
                if (quick == 0 || quick == 8) continue;
                int above = 0;
                int x[8], y[8], z[8];
                glm::vec3 out[8];
                for (int c = 0; c < 8; ++c) {
                    const int si = i + (c & 1), sj = j + (c >> 1 & 1), sk = k + (c >> 2 & 1);
                    x[c] = s.cell(si, s.sx, s.grid.nx), y[c] = s.cell(sj, s.sy, s.grid.ny), z[c] = s.cell(sk, s.sz, s.grid.nz);
                    out[c] = glm::vec3(si < 0 ? -1.0f : si >= s.sx ? 1.0f : 0.0f, sj < 0 ? -1.0f : sj >= s.sy ? 1.0f : 0.0f,
                                       sk < 0 ? -1.0f : sk >= s.sz ? 1.0f : 0.0f);
                    corner[c].beyond = out[c] != glm::vec3(0);
                    corner[c].value = corner[c].beyond ? -std::numeric_limits<double>::infinity()
                                                       : s.value_at(x[c], y[c], z[c]);
                    above += corner[c].value > level;
                }
                if (above == 0 || above == 8) continue;
                if (!going) return;
                for (int c = 0; c < 8; ++c) {
                    corner[c].position = glm::vec3(float(x[c]), float(y[c]), float(z[c]));
                    corner[c].normal = corner[c].beyond ? out[c] : s.normal_at(x[c], y[c], z[c]);
                }
                for (const auto& t : tetrahedra) {
                    int in[4], below[4], n_in = 0, n_below = 0;
                    for (int v : t) (corner[v].value > level ? in[n_in++] : below[n_below++]) = v;
                    if (n_in == 0 || n_below == 0) continue;
                    if (n_in == 1 || n_below == 1) {
                        // One corner apart from the other three: a triangle across its three edges.
                        const int lone = n_in == 1 ? in[0] : below[0];
                        const int* rest = n_in == 1 ? below : in;
                        triangle(cut(corner[lone], corner[rest[0]]), cut(corner[lone], corner[rest[1]]),
                                 cut(corner[lone], corner[rest[2]]));
                    } else {
                        // Two and two: a quad across four edges, as two triangles.
                        const Point p = cut(corner[in[0]], corner[below[0]]), q = cut(corner[in[0]], corner[below[1]]),
                                    r = cut(corner[in[1]], corner[below[1]]), u = cut(corner[in[1]], corner[below[0]]);
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
    return {grid, stride, samples(grid.nx), samples(grid.ny), samples(grid.nz), grid.capped,
            grid.inside_below ? -1.0 : 1.0};
}

}  // namespace

namespace {

// The facets at `stride`, or stopped once there are more than `most`.
// The layers of cubes are walked side by side on the run's threads, each
// into facets of its own, laid end to end in the order of the layers: the
// facets of one walk in the same order. Past the budget every layer stops
// (the facets then number more than `most`).
std::vector<Facet> facets_at(const IsosurfaceGrid& grid, double level, const glm::vec4& colour, int stride,
                             long long most) {
    const Sampled s = sampled(grid, level, stride);
    const double at = s.sign * level;
    const std::vector<std::uint8_t> up = above_level(s, at);
    const int first = first_layer(s), layers = std::max(0, last_layer(s) - first);
    std::vector<std::vector<Facet>> parts(static_cast<std::size_t>(layers));
    // The facets made so far, counted in batches (a layer passes the
    // budget by at most a batch before it stops).
    constexpr long long batch = 64;
    std::atomic<long long> made{0};
#pragma omp parallel for schedule(dynamic)
    for (int t = 0; t < layers; ++t) {
        if (made.load(std::memory_order_relaxed) > most) continue;
        std::vector<Facet>& facets = parts[static_cast<std::size_t>(t)];
        march(s, at, up, first + t, first + t + 1,
              [&](glm::vec3 a, glm::vec3 na, glm::vec3 b, glm::vec3 nb, glm::vec3 c, glm::vec3 nc) {
                  facets.push_back({a, b, c, colour, na, nb, nc});
                  if (static_cast<long long>(facets.size()) % batch) return true;
                  return made.fetch_add(batch, std::memory_order_relaxed) + batch <= most;
              });
        made.fetch_add(static_cast<long long>(facets.size()) % batch, std::memory_order_relaxed);
    }
    std::size_t total = 0;
    for (const auto& part : parts) total += part.size();
    std::vector<Facet> facets;
    facets.reserve(total);
    for (auto& part : parts) {
        facets.insert(facets.end(), part.begin(), part.end());
        std::vector<Facet>().swap(part);  // each layer's memory given back as it is copied
    }
    return facets;
}

}  // namespace

std::vector<Facet> isosurface(const IsosurfaceGrid& grid, double level, const glm::vec4& colour, int stride) {
    return facets_at(grid, level, colour, stride, std::numeric_limits<long long>::max());
}

std::vector<Facet> isosurface_within(const IsosurfaceGrid& grid, double level, const glm::vec4& colour,
                                     long long most_facets, int* stride_used) {
    // One walk a stride, stopped as soon as it passes the budget: most
    // surfaces are done in the first.
    for (int stride = 1;; ++stride) {
        const bool last = stride >= std::max({grid.nx, grid.ny, grid.nz});
        std::vector<Facet> facets = facets_at(grid, level, colour, stride, last ? std::numeric_limits<long long>::max() : most_facets);
        if (static_cast<long long>(facets.size()) <= most_facets || last) {
            if (stride_used) *stride_used = stride;
            return facets;
        }
    }
}

}  // namespace render
