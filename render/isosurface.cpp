#include "render/isosurface.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace render {
namespace {

// A cube's corners: corner k at (k & 1, k >> 1 & 1, k >> 2 & 1); its twelve
// edges join the corners one bit apart.
struct Edge {
    int from, to;
};

// Per case (bit k: corner k above the level), the triangles as edges of
// the cube, three a triangle; made once from the faces (cube_cases()).
struct Case {
    std::uint8_t triangles = 0;
    std::array<std::uint8_t, 36> edges{};  // at most 12 triangles (a cube has 12 edges)
};

struct Cases {
    std::array<Edge, 12> edge{};
    std::array<Case, 256> of{};
};

// The cases, from the cube's six faces. Walked counter-clockwise seen from
// outside the cube, a face's crossed edges alternate between entries (from
// a corner below the level to one above) and exits; each entry joins the
// next exit, which cuts off the face's corners above the level on their
// own (a face with two such corners on a diagonal keeps them apart). The
// two cubes that share a face see it the same way, so the surface has no
// cracks. A crossed edge is the entry of one of its two faces and the exit
// of the other: the joins close into loops, each a polygon of the surface,
// cut into triangles as a fan.
Cases cube_cases() {
    Cases t;
    int index[8][8];
    int n = 0;
    for (int a = 0; a < 8; ++a)
        for (int b = a + 1; b < 8; ++b)
            if (std::popcount(static_cast<unsigned>(a ^ b)) == 1) {
                t.edge[n] = {a, b};
                index[a][b] = index[b][a] = n++;
            }
    // Each face's corners counter-clockwise about its outward normal: with
    // u, v the axes after `axis` in turn, (0,0) (1,0) (1,1) (0,1) turns
    // about +axis.
    std::array<std::array<int, 4>, 6> faces{};
    for (int axis = 0, f = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side, ++f) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const int uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (int i = 0; i < 4; ++i) {
                const int k = side ? i : (4 - i) % 4;  // about -axis: the other way round
                faces[f][i] = side << axis | uv[k][0] << u | uv[k][1] << v;
            }
        }
    for (int bits = 0; bits < 256; ++bits) {
        auto above = [&](int corner) { return (bits >> corner & 1) != 0; };
        std::array<int, 12> next;
        next.fill(-1);
        for (const auto& face : faces)
            for (int i = 0; i < 4; ++i) {
                if (above(face[i]) || !above(face[(i + 1) % 4])) continue;  // not an entry
                for (int j = i + 1; j < i + 4; ++j)
                    if (above(face[j % 4]) && !above(face[(j + 1) % 4])) {
                        next[index[face[i]][face[(i + 1) % 4]]] = index[face[j % 4]][face[(j + 1) % 4]];
                        break;
                    }
            }
        Case& c = t.of[bits];
        std::array<bool, 12> seen{};
        for (int e = 0; e < 12; ++e) {
            if (next[e] < 0 || seen[e]) continue;
            std::array<int, 12> loop;
            int length = 0;
            for (int at = e; !seen[at]; at = next[at]) {
                seen[at] = true;
                loop[length++] = at;
            }
            for (int k = 1; k + 1 < length; ++k) {
                const int tri = c.triangles++;
                c.edges[3 * tri] = static_cast<std::uint8_t>(loop[0]);
                c.edges[3 * tri + 1] = static_cast<std::uint8_t>(loop[k]);
                c.edges[3 * tri + 2] = static_cast<std::uint8_t>(loop[k + 1]);
            }
        }
    }
    return t;
}

const Cases& cases() {
    static const Cases t = cube_cases();
    return t;
}

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
    // The cubes walked: from -1 on each axis to one sample past the far
    // face when capped (a sample there is below the level and its normal
    // faces out; an edge from a corner on the face to it is cut at that
    // corner, so the region above the level is closed by flat caps on the
    // grid's faces), else between the samples.
    int first() const { return capped ? -1 : 0; }
    int cubes(int samples) const { return std::max(0, samples - 1 + (capped ? 2 : 0)); }
};

// Which samples lie above the level (those past a face never), indexed
// from -1 on each axis: a cube's case is eight bytes away.
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

// The case of the cube whose lowest corner is sample (i, j, k).
struct CaseOf {
    const std::vector<std::uint8_t>& up;
    std::size_t px, py;
    int operator()(int i, int j, int k) const {
        const std::size_t at = (static_cast<std::size_t>(k + 1) * py + static_cast<std::size_t>(j + 1)) * px +
                               static_cast<std::size_t>(i + 1);
        const std::uint8_t* p = up.data() + at;
        const std::size_t row = px, plane = px * py;
        return p[0] | p[1] << 1 | p[row] << 2 | p[row + 1] << 3 | p[plane] << 4 | p[plane + 1] << 5 |
               p[plane + row] << 6 | p[plane + row + 1] << 7;
    }
};

// The facets of each layer of cubes (k from s.first() on), counted from the cases alone.
std::vector<long long> facets_per_layer(const Sampled& s, const std::vector<std::uint8_t>& up) {
    const Cases& t = cases();
    const CaseOf case_of{up, static_cast<std::size_t>(s.sx + 2), static_cast<std::size_t>(s.sy + 2)};
    const int layers = s.cubes(s.sz), rows = s.cubes(s.sy), columns = s.cubes(s.sx), first = s.first();
    std::vector<long long> count(static_cast<std::size_t>(layers), 0);
#pragma omp parallel for schedule(static)
    for (int layer = 0; layer < layers; ++layer) {
        long long n = 0;
        for (int j = first; j < first + rows; ++j)
            for (int i = first; i < first + columns; ++i) n += t.of[static_cast<std::size_t>(case_of(i, j, first + layer))].triangles;
        count[static_cast<std::size_t>(layer)] = n;
    }
    return count;
}

// Writes the facets of layer k of cubes from `out` on, in the order of the
// cubes (x fastest) and of each case's triangles; each wound to face along
// its corners' normals.
void march_layer(const Sampled& s, double level, const std::vector<std::uint8_t>& up, int k, const glm::vec4& colour,
                 Facet* out) {
    const Cases& t = cases();
    const CaseOf case_of{up, static_cast<std::size_t>(s.sx + 2), static_cast<std::size_t>(s.sy + 2)};
    struct Point {
        glm::vec3 position, normal;
    };
    struct Corner {
        glm::vec3 position, normal;
        double value;
        bool beyond;  // a sample past a face of the grid (capping): below the level, its normal facing out
    };
    std::array<Corner, 8> corner;
    std::array<Point, 12> point;
    const int first = s.first();
    for (int j = first; j < first + s.cubes(s.sy); ++j)
        for (int i = first; i < first + s.cubes(s.sx); ++i) {
            const int bits = case_of(i, j, k);
            const Case& c = t.of[static_cast<std::size_t>(bits)];
            if (c.triangles == 0) continue;
            for (int n = 0; n < 8; ++n) {
                const int si = i + (n & 1), sj = j + (n >> 1 & 1), sk = k + (n >> 2 & 1);
                const glm::vec3 outward(si < 0 ? -1.0f : si >= s.sx ? 1.0f : 0.0f, sj < 0 ? -1.0f : sj >= s.sy ? 1.0f : 0.0f,
                                        sk < 0 ? -1.0f : sk >= s.sz ? 1.0f : 0.0f);
                const int x = s.cell(si, s.sx, s.grid.nx), y = s.cell(sj, s.sy, s.grid.ny), z = s.cell(sk, s.sz, s.grid.nz);
                Corner& p = corner[static_cast<std::size_t>(n)];
                p.beyond = outward != glm::vec3(0);
                p.position = glm::vec3(float(x), float(y), float(z));
                p.value = p.beyond ? -std::numeric_limits<double>::infinity() : s.value_at(x, y, z);
                p.normal = p.beyond ? outward : glm::vec3(0);
            }
            // Each crossed edge's point, always from the corner above the level
            // to the one below: the cubes that share an edge put its point at
            // the same bits. Past a face, the cap's corner is the inside corner
            // itself, which lies on the face.
            std::array<bool, 8> normal_known{};
            auto normal_of = [&](int n) -> const glm::vec3& {
                Corner& p = corner[static_cast<std::size_t>(n)];
                if (!p.beyond && !normal_known[static_cast<std::size_t>(n)]) {
                    p.normal = s.normal_at(int(p.position.x), int(p.position.y), int(p.position.z));
                    normal_known[static_cast<std::size_t>(n)] = true;
                }
                return p.normal;
            };
            std::array<bool, 12> cut{};
            for (int e = 0; e < 3 * c.triangles; ++e) {
                const int edge = c.edges[static_cast<std::size_t>(e)];
                if (cut[static_cast<std::size_t>(edge)]) continue;
                cut[static_cast<std::size_t>(edge)] = true;
                const int from = t.edge[static_cast<std::size_t>(edge)].from, to = t.edge[static_cast<std::size_t>(edge)].to;
                const bool from_above = bits >> from & 1;
                const int ia = from_above ? from : to, ib = from_above ? to : from;
                const Corner& a = corner[static_cast<std::size_t>(ia)];
                const Corner& b = corner[static_cast<std::size_t>(ib)];
                Point& q = point[static_cast<std::size_t>(edge)];
                if (b.beyond) {
                    q = {a.position, b.normal};
                } else {
                    const glm::vec3 na = normal_of(ia), nb = normal_of(ib);
                    const double along = (level - a.value) / (b.value - a.value);
                    const float f = static_cast<float>(std::clamp(along, 0.0, 1.0));
                    q = {a.position + f * (b.position - a.position), na + f * (nb - na)};
                }
            }
            for (int tri = 0; tri < c.triangles; ++tri) {
                const Point& a = point[c.edges[static_cast<std::size_t>(3 * tri)]];
                const Point& b = point[c.edges[static_cast<std::size_t>(3 * tri + 1)]];
                const Point& d = point[c.edges[static_cast<std::size_t>(3 * tri + 2)]];
                const glm::vec3 across = glm::cross(b.position - a.position, d.position - a.position);
                if (glm::dot(across, a.normal + b.normal + d.normal) < 0)
                    *out++ = {a.position, d.position, b.position, colour, a.normal, d.normal, b.normal};
                else
                    *out++ = {a.position, b.position, d.position, colour, a.normal, b.normal, d.normal};
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

// The facets at `stride`, or none when they would number more than `most`
// (*counted: how many). Counted first from the cases, each layer of cubes
// then writes its own part of one array, the layers side by side on the
// run's threads: the same facets in the same order on any number.
std::vector<Facet> facets_at(const IsosurfaceGrid& grid, double level, const glm::vec4& colour, int stride,
                             long long most, long long* counted = nullptr) {
    const Sampled s = sampled(grid, level, stride);
    const double at = s.sign * level;
    const std::vector<std::uint8_t> up = above_level(s, at);
    const std::vector<long long> per_layer = facets_per_layer(s, up);
    std::vector<long long> start(per_layer.size() + 1, 0);
    std::partial_sum(per_layer.begin(), per_layer.end(), start.begin() + 1);
    const long long total = start.back();
    if (counted) *counted = total;
    if (total > most) return {};
    std::vector<Facet> facets(static_cast<std::size_t>(total));
    const int layers = static_cast<int>(per_layer.size());
#pragma omp parallel for schedule(dynamic)
    for (int layer = 0; layer < layers; ++layer)
        if (per_layer[static_cast<std::size_t>(layer)] > 0)
            march_layer(s, at, up, s.first() + layer, colour, facets.data() + start[static_cast<std::size_t>(layer)]);
    return facets;
}

}  // namespace

std::vector<Facet> isosurface(const IsosurfaceGrid& grid, double level, const glm::vec4& colour, int stride) {
    return facets_at(grid, level, colour, stride, std::numeric_limits<long long>::max());
}

std::vector<Facet> isosurface_within(const IsosurfaceGrid& grid, double level, const glm::vec4& colour,
                                     long long most_facets, int* stride_used) {
    // The facets of each stride are counted before any is made: one walk.
    for (int stride = 1;; ++stride) {
        const bool last = stride >= std::max({grid.nx, grid.ny, grid.nz});
        long long counted = 0;
        std::vector<Facet> facets =
            facets_at(grid, level, colour, stride, last ? std::numeric_limits<long long>::max() : most_facets, &counted);
        if (counted <= most_facets || last) {
            if (stride_used) *stride_used = stride;
            return facets;
        }
    }
}

}  // namespace render
