#include "sim/mesh/mesh.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

namespace sim::mesh {
namespace {

using Ids = std::span<const std::int64_t>;

// Each cell type's edges and faces, as local point indices in VTK 9.1's
// order (vtkTriangle, vtkQuad, vtkTetra, vtkVoxel, vtkHexahedron, vtkWedge,
// vtkPyramid: their GetEdge and GetFace). Polygons and polyhedra have none
// fixed: their edges run round the points, or round each face.
using Table = std::vector<std::vector<int>>;

const Table& edge_table(std::uint8_t type) {
    static const Table none, triangle = {{0, 1}, {1, 2}, {2, 0}}, quad = {{0, 1}, {1, 2}, {2, 3}, {3, 0}},
                             tetra = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}},
                             voxel = {{0, 1}, {1, 3}, {2, 3}, {0, 2}, {4, 5}, {5, 7}, {6, 7}, {4, 6}, {0, 4}, {1, 5},
                                      {2, 6}, {3, 7}},
                             hexahedron = {{0, 1}, {1, 2}, {3, 2}, {0, 3}, {4, 5}, {5, 6}, {7, 6}, {4, 7}, {0, 4},
                                           {1, 5}, {3, 7}, {2, 6}},
                             wedge = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}},
                             pyramid = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 4}, {2, 4}, {3, 4}};
    switch (type) {
    case cell_type::triangle: return triangle;
    case cell_type::quad: return quad;
    case cell_type::tetra: return tetra;
    case cell_type::voxel: return voxel;
    case cell_type::hexahedron: return hexahedron;
    case cell_type::wedge: return wedge;
    case cell_type::pyramid: return pyramid;
    default: return none;
    }
}

const Table& face_table(std::uint8_t type) {
    static const Table none, tetra = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 2, 1}},
                             voxel = {{2, 0, 6, 4}, {1, 3, 5, 7}, {0, 1, 4, 5}, {3, 2, 7, 6}, {1, 0, 3, 2}, {4, 5, 6, 7}},
                             hexahedron = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                           {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}},
                             wedge = {{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}},
                             pyramid = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    switch (type) {
    case cell_type::tetra: return tetra;
    case cell_type::voxel: return voxel;
    case cell_type::hexahedron: return hexahedron;
    case cell_type::wedge: return wedge;
    case cell_type::pyramid: return pyramid;
    default: return none;
    }
}

// The points a cell of `type` has: exactly, or (polygon, polyhedron) at least.
struct PointCount {
    std::int64_t least = 0;
    bool exact = true;
};

bool known_type(std::uint8_t type) {
    return type == cell_type::triangle || type == cell_type::polygon || type == cell_type::quad ||
           type == cell_type::tetra || type == cell_type::voxel || type == cell_type::hexahedron ||
           type == cell_type::wedge || type == cell_type::pyramid || type == cell_type::polyhedron;
}

PointCount point_count(std::uint8_t type) {
    switch (type) {
    case cell_type::triangle: return {3, true};
    case cell_type::quad:
    case cell_type::tetra: return {4, true};
    case cell_type::voxel:
    case cell_type::hexahedron: return {8, true};
    case cell_type::wedge: return {6, true};
    case cell_type::pyramid: return {5, true};
    case cell_type::polygon: return {3, false};
    default: return {4, false};  // polyhedron
    }
}

std::string cell_text(std::size_t c) { return "cell " + std::to_string(c); }

Ids points_of(const Mesh& m, std::size_t c) {
    const auto from = static_cast<std::size_t>(m.offsets[c]), to = static_cast<std::size_t>(m.offsets[c + 1]);
    return Ids(m.point_ids).subspan(from, to - from);
}

// A polyhedron's faces, each as its points: walks the face stream from `at`.
struct FaceStream {
    const Mesh& m;
    std::size_t at;  // the polyhedron's face count

    std::int64_t count() const { return m.faces[at]; }
    template <class F>
    void each(F&& f) const {
        std::size_t p = at + 1;
        for (std::int64_t i = 0; i < count(); ++i) {
            const auto n = static_cast<std::size_t>(m.faces[p]);
            f(Ids(m.faces).subspan(p + 1, n));
            p += n + 1;
        }
    }
};

// Where each polyhedron's face stream starts (checked: check() walked it).
std::vector<std::size_t> face_starts(const Mesh& m) {
    std::vector<std::size_t> starts(m.cell_count(), 0);
    std::size_t at = 0;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        if (m.types[c] != cell_type::polyhedron) continue;
        starts[c] = at;
        at = static_cast<std::size_t>(m.face_offsets[c]);
    }
    return starts;
}

// VTK 9.1's cell links (vtkStaticCellLinks): for each point the cells that
// list it, a cell once for each time it lists the point. Their order within
// a point does not matter here: VTK's GetCellNeighbors sorts what it finds.
struct Links {
    std::vector<std::size_t> start;  // points + 1
    std::vector<int> cells;

    explicit Links(const Mesh& m) : start(m.point_count() + 1, 0), cells(m.point_ids.size()) {
        for (std::int64_t p : m.point_ids) ++start[static_cast<std::size_t>(p) + 1];
        for (std::size_t p = 0; p < m.point_count(); ++p) start[p + 1] += start[p];
        std::vector<std::size_t> next(start.begin(), start.end() - 1);
        for (std::size_t c = 0; c < m.cell_count(); ++c)
            for (std::int64_t p : points_of(m, c)) cells[next[static_cast<std::size_t>(p)]++] = static_cast<int>(c);
    }
};

class Finder {
public:
    explicit Finder(const Mesh& m) : m_(m), links_(m), starts_(face_starts(m)) {}

    // What finding every cell's neighbours costs, in the cells the links of
    // its points pool (each pass over them sorts that many): the sum over
    // cells of that count squared, as a vertex neighbourhood's ring passes
    // over them about as often as it finds cells.
    double work() const {
        double w = 0;
        for (std::size_t c = 0; c < m_.cell_count(); ++c) {
            double pooled = 0;
            for (std::int64_t p : points_of(m_, c))
                pooled += static_cast<double>(links_.start[static_cast<std::size_t>(p) + 1] -
                                              links_.start[static_cast<std::size_t>(p)]);
            w += pooled * pooled;
        }
        return w;
    }

    // vtkUnstructuredGrid::GetCellNeighbors(cell, pts) in VTK 9.1: the links
    // of every point of `pts` put together and sorted; a cell is a
    // neighbour when its run is at least as long as `pts` (so a cell that
    // lists a point twice counts it twice), and it is not `cell`. Each once,
    // in increasing index.
    const std::vector<int>& sharing(int cell, Ids pts) {
        found_.clear();
        if (pts.empty()) return found_;
        pooled_.clear();
        for (std::int64_t p : pts) {
            const auto q = static_cast<std::size_t>(p);
            pooled_.insert(pooled_.end(), links_.cells.begin() + static_cast<std::ptrdiff_t>(links_.start[q]),
                           links_.cells.begin() + static_cast<std::ptrdiff_t>(links_.start[q + 1]));
        }
        std::sort(pooled_.begin(), pooled_.end());
        for (std::size_t i = 0; i < pooled_.size();) {
            std::size_t j = i;
            while (j < pooled_.size() && pooled_[j] == pooled_[i]) ++j;
            if (j - i >= pts.size() && pooled_[i] != cell) found_.push_back(pooled_[i]);
            i = j;
        }
        return found_;
    }

    // The cell's edges (vtkCell::GetEdge in order), each as its two points;
    // a polyhedron's repeated (`unique` false: for asking whether an edge
    // is there, where repeats change nothing and finding them costs).
    template <class F>
    void each_edge(std::size_t c, F&& f, bool unique = true) const {
        const Ids pts = points_of(m_, c);
        const std::uint8_t type = m_.types[c];
        if (type == cell_type::polygon) {
            for (std::size_t i = 0; i < pts.size(); ++i) {
                const std::int64_t e[2] = {pts[i], pts[(i + 1) % pts.size()]};
                f(Ids(e));
            }
        } else if (type == cell_type::polyhedron) {
            // vtkPolyhedron::GenerateEdges: round each face in turn, each
            // edge (either way round) where it first comes.
            std::vector<std::int64_t> seen;
            FaceStream{m_, starts_[c]}.each([&](Ids face) {
                for (std::size_t i = 0; i < face.size(); ++i) {
                    const std::int64_t e[2] = {face[i], face[(i + 1) % face.size()]};
                    bool known = false;
                    for (std::size_t k = 0; unique && k < seen.size() && !known; k += 2)
                        known = (seen[k] == e[0] && seen[k + 1] == e[1]) || (seen[k] == e[1] && seen[k + 1] == e[0]);
                    if (known) continue;
                    seen.insert(seen.end(), e, e + 2);
                    f(Ids(e));
                }
            });
        } else {
            for (const auto& local : edge_table(type)) {
                const std::int64_t e[2] = {pts[static_cast<std::size_t>(local[0])], pts[static_cast<std::size_t>(local[1])]};
                f(Ids(e));
            }
        }
    }

    // The cell's faces (vtkCell::GetFace in order), each as its points.
    template <class F>
    void each_face(std::size_t c, F&& f) const {
        const std::uint8_t type = m_.types[c];
        if (type == cell_type::polyhedron) {
            FaceStream{m_, starts_[c]}.each(f);
            return;
        }
        const Ids pts = points_of(m_, c);
        std::vector<std::int64_t> face;
        for (const auto& local : face_table(type)) {
            face.clear();
            for (int i : local) face.push_back(pts[static_cast<std::size_t>(i)]);
            f(Ids(face));
        }
    }

    // Ready's IsEdgeNeighbor(c1, c2): c2 among the cells GetCellNeighbors
    // finds for some edge of c1; that is, c2 is not c1 and lists that
    // edge's points (counted as VTK counts them) at least twice.
    bool edge_neighbour(int c1, int c2) const {
        if (c1 == c2) return false;
        const Ids other = points_of(m_, static_cast<std::size_t>(c2));
        bool shared = false;
        each_edge(static_cast<std::size_t>(c1), [&](Ids edge) {
            if (shared) return;
            std::size_t uses = 0;
            for (std::int64_t p : edge) uses += static_cast<std::size_t>(std::count(other.begin(), other.end(), p));
            shared = uses >= edge.size();
        }, false);
        return shared;
    }

private:
    const Mesh& m_;
    Links links_;
    std::vector<std::size_t> starts_;
    std::vector<int> pooled_, found_;
};

void add_if_new(std::vector<int>& found, int n) {
    if (std::find(found.begin(), found.end(), n) == found.end()) found.push_back(n);
}

template <class Real>
std::vector<Real> laplacian_of(const Neighbours& n, const std::vector<Real>& x, bool fused) {
    const auto slots = static_cast<std::size_t>(n.max_neighbors);
    if (n.indices.size() != x.size() * slots || n.weights.size() != n.indices.size())
        throw std::invalid_argument("laplacian: " + std::to_string(x.size()) + " values for neighbour lists of " +
                                    std::to_string(n.indices.size()) + " slots");
    std::vector<Real> out(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        Real sum = -x[i];
        for (std::size_t k = i * slots; k < (i + 1) * slots; ++k) {
            const auto j = static_cast<std::size_t>(n.indices[k]);
            if (j >= x.size()) throw std::invalid_argument("laplacian: a neighbour index is past the cells");
            const Real w = static_cast<Real>(n.weights[k]);
            sum = fused ? std::fma(x[j], w, sum) : sum + x[j] * w;
        }
        out[i] = sum * Real(4);
    }
    return out;
}

}  // namespace

void check(const Mesh& m) {
    const auto fail = [](const std::string& what) { throw std::invalid_argument("mesh: " + what); };
    if (m.points.size() % 3 != 0) fail(std::to_string(m.points.size()) + " coordinates, not x, y, z of each point");
    for (double v : m.points)
        if (!std::isfinite(v)) fail("a point's coordinate is not a finite number");
    const std::size_t cells = m.cell_count();
    if (m.offsets.size() != cells + 1)
        fail(std::to_string(m.offsets.size()) + " offsets for " + std::to_string(cells) + " cells; one more is needed");
    if (m.offsets.front() != 0) fail("the first offset is " + std::to_string(m.offsets.front()) + ", not 0");
    if (static_cast<std::uint64_t>(m.offsets.back()) != m.point_ids.size())
        fail("the last offset is " + std::to_string(m.offsets.back()) + ", not the " +
             std::to_string(m.point_ids.size()) + " point indices");
    const auto points = static_cast<std::int64_t>(m.point_count());
    for (std::int64_t p : m.point_ids)
        if (p < 0 || p >= points)
            fail("a point index is " + std::to_string(p) + ", outside the " + std::to_string(points) + " points");
    bool polyhedra = false;
    for (std::size_t c = 0; c < cells; ++c) {
        const std::uint8_t type = m.types[c];
        if (!known_type(type))
            fail(cell_text(c) + " is of VTK type " + std::to_string(type) +
                 "; figgen reads 5, 7, 9, 10, 11, 12, 13, 14 and 42");
        const std::int64_t n = m.offsets[c + 1] - m.offsets[c];
        const PointCount want = point_count(type);
        if (n < want.least || n > max_cell_points || (want.exact && n != want.least))
            fail(cell_text(c) + " of VTK type " + std::to_string(type) + " has " + std::to_string(n) + " points, not " +
                 (want.exact ? std::to_string(want.least)
                             : std::to_string(want.least) + " to " + std::to_string(max_cell_points)));
        polyhedra = polyhedra || type == cell_type::polyhedron;
    }
    if (!polyhedra) {
        if (!m.faces.empty()) fail("it has faces but no polyhedra");
        for (std::int64_t o : m.face_offsets)
            if (o != -1) fail("a face offset is " + std::to_string(o) + " but no cell is a polyhedron");
        if (!m.face_offsets.empty() && m.face_offsets.size() != cells) fail("its face offsets are not one a cell");
        return;
    }
    if (m.face_offsets.size() != cells)
        fail(std::to_string(m.face_offsets.size()) + " face offsets for " + std::to_string(cells) + " cells");
    // Each polyhedron's face stream, in turn: its counts within bounds and
    // within the array, before any is used to reach further.
    std::size_t at = 0;
    std::vector<std::int64_t> own;
    for (std::size_t c = 0; c < cells; ++c) {
        if (m.types[c] != cell_type::polyhedron) {
            if (m.face_offsets[c] != -1)
                fail(cell_text(c) + " is not a polyhedron, but its face offset is " + std::to_string(m.face_offsets[c]));
            continue;
        }
        const auto need = [&](std::size_t n) {
            if (m.faces.size() - at < n) fail(cell_text(c) + "'s faces run past the faces array");
        };
        need(1);
        const std::int64_t count = m.faces[at++];
        if (count < 1 || count > max_cell_faces)
            fail(cell_text(c) + " has " + std::to_string(count) + " faces, not 1 to " + std::to_string(max_cell_faces));
        const Ids pts = points_of(m, c);
        own.assign(pts.begin(), pts.end());
        std::sort(own.begin(), own.end());
        for (std::int64_t f = 0; f < count; ++f) {
            need(1);
            const std::int64_t n = m.faces[at++];
            if (n < 3 || n > max_cell_points)
                fail(cell_text(c) + "'s face " + std::to_string(f) + " has " + std::to_string(n) + " points, not 3 to " +
                     std::to_string(max_cell_points));
            need(static_cast<std::size_t>(n));
            for (std::int64_t i = 0; i < n; ++i, ++at)
                if (!std::binary_search(own.begin(), own.end(), m.faces[at]))
                    fail(cell_text(c) + "'s face " + std::to_string(f) + " names a point that is not among the cell's");
        }
        if (m.face_offsets[c] < 0 || static_cast<std::uint64_t>(m.face_offsets[c]) != at)
            fail(cell_text(c) + "'s face offset is " + std::to_string(m.face_offsets[c]) + "; its faces end at " +
                 std::to_string(at));
    }
    if (at != m.faces.size())
        fail("the faces array holds " + std::to_string(m.faces.size()) + " numbers; the polyhedra use " +
             std::to_string(at));
}

Neighbours neighbours(const Mesh& m, Kind kind) {
    check(m);
    const std::size_t cells = m.cell_count();
    if (cells > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw std::invalid_argument("mesh: more cells than Ready's int indices hold");
    for (std::uint8_t type : m.types)
        if (type != m.types.front())
            throw std::invalid_argument("mesh: its cells are of more than one type; Ready runs meshes of one");
    Finder finder(m);
    if (const double work = finder.work(); work > max_neighbour_work) {
        char said[160];
        std::snprintf(said, sizeof said,
                      "mesh: its cells share points with so many others that finding their neighbours would take "
                      "%.2g steps; figgen takes at most %.2g", work, max_neighbour_work);
        throw std::invalid_argument(said);
    }
    std::vector<std::vector<int>> lists(cells);
    std::vector<int> about;  // a cell's neighbours by each of its points in turn
    std::vector<std::size_t> about_start;
    Neighbours out;
    for (std::size_t c = 0; c < cells; ++c) {
        const int cell = static_cast<int>(c);
        std::vector<int>& found = lists[c];
        const auto from_each = [&](Ids pts) {
            for (int n : finder.sharing(cell, pts)) add_if_new(found, n);
        };
        switch (kind) {
        case Kind::vertex: {
            const Ids pts = points_of(m, c);
            // The cells about each point, found once.
            about.clear();
            about_start.assign(1, 0);
            for (std::size_t i = 0; i < pts.size(); ++i) {
                const std::vector<int>& sharing = finder.sharing(cell, pts.subspan(i, 1));
                about.insert(about.end(), sharing.begin(), sharing.end());
                about_start.push_back(about.size());
            }
            // Round and round the points, taking a cell only when it shares
            // an edge with the last one taken: Ready's way of listing them
            // in a ring about the cell. (A cell already taken is passed
            // over before the edge test, which would change nothing.)
            std::size_t before = 0;
            do {
                before = found.size();
                for (std::size_t i = 0; i < pts.size(); ++i)
                    for (std::size_t k = about_start[i]; k < about_start[i + 1]; ++k) {
                        const int n = about[k];
                        if (std::find(found.begin(), found.end(), n) != found.end()) continue;
                        if (found.empty() || finder.edge_neighbour(found.back(), n)) found.push_back(n);
                    }
            } while (found.size() > before);
            // Then any left (where the mesh is not a manifold).
            for (int n : about) add_if_new(found, n);
            break;
        }
        case Kind::edge: finder.each_edge(c, from_each); break;
        case Kind::face: finder.each_face(c, from_each); break;
        }
        out.max_neighbors = std::max({out.max_neighbors, static_cast<int>(found.size()), 1});
    }
    const auto slots = static_cast<std::size_t>(out.max_neighbors);
    out.indices.resize(cells * slots);
    out.weights.resize(cells * slots);
    for (std::size_t c = 0; c < cells; ++c) {
        // Ready's normalisation: weights of 1.0f summed in float, the sum
        // kept from 0 (1e-5f), each weight divided by it.
        float sum = 0.0f;
        for (std::size_t j = 0; j < lists[c].size(); ++j) sum += 1.0f;
        sum = std::max(sum, 1e-5f);
        for (std::size_t j = 0; j < slots; ++j) {
            const bool real = j < lists[c].size();
            out.indices[c * slots + j] = real ? lists[c][j] : static_cast<int>(c);
            out.weights[c * slots + j] = real ? 1.0f / sum : 0.0f;
        }
    }
    return out;
}

std::vector<float> laplacian(const Neighbours& n, const std::vector<float>& x, bool fused) {
    return laplacian_of(n, x, fused);
}

std::vector<double> laplacian(const Neighbours& n, const std::vector<double>& x, bool fused) {
    return laplacian_of(n, x, fused);
}

}  // namespace sim::mesh
