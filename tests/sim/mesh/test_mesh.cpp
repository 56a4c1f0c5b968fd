// Ready's meshes (sim/mesh/mesh.cpp): the neighbour lists are the ones Ready
// makes through VTK, in its order, padding and weights (against VTK
// itself: tests/sim/mesh/ready_neighbours.py, whose lists for small meshes
// of every cell type are expected.json, made by make_fixtures.py), and the
// Laplacian is its formula kernel's, in its order of operations.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"
#include "ready/vtu.hpp"
#include "sim/mesh/mesh.hpp"

namespace fs = std::filesystem;
using sim::mesh::Kind;
using sim::mesh::Mesh;
using sim::mesh::Neighbours;

namespace {

const fs::path fixtures = fs::path(FIGGEN_SOURCE_DIR) / "tests/sim/mesh";

const std::pair<const char*, Kind> kinds[] = {{"vertex", Kind::vertex}, {"edge", Kind::edge}, {"face", Kind::face}};

// figgen's lists against ready_neighbours.py's JSON for them, exactly.
void check_against(const Neighbours& n, const nlohmann::json& expected) {
    REQUIRE(n.max_neighbors == expected["max_neighbors"].get<int>());
    CHECK(n.indices == expected["indices"].get<std::vector<int>>());
    const auto weights = expected["weights"].get<std::vector<double>>();
    REQUIRE(weights.size() == n.weights.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < weights.size(); ++i) differ += static_cast<float>(weights[i]) != n.weights[i];
    CHECK(differ == 0);
}

Mesh mesh_of(std::vector<double> points, const std::vector<std::vector<std::int64_t>>& cells, std::uint8_t type) {
    Mesh m;
    m.points = std::move(points);
    for (const auto& c : cells) {
        m.point_ids.insert(m.point_ids.end(), c.begin(), c.end());
        m.offsets.push_back(static_cast<std::int64_t>(m.point_ids.size()));
        m.types.push_back(type);
    }
    return m;
}

// Ready's kernel as FormulaOpenCLMeshRD.cpp writes it, one cell at a time:
//   laplacian = -x; for each slot: laplacian += x_in[index] * weight; laplacian *= 4
float kernel_laplacian(const Neighbours& n, const std::vector<float>& x, std::size_t cell, bool fused) {
    float sum = -x[cell];
    for (int k = 0; k < n.max_neighbors; ++k) {
        const std::size_t slot = cell * static_cast<std::size_t>(n.max_neighbors) + static_cast<std::size_t>(k);
        const float v = x[static_cast<std::size_t>(n.indices[slot])];
        sum = fused ? std::fma(v, n.weights[slot], sum) : sum + v * n.weights[slot];
    }
    return sum * 4.0f;
}

}  // namespace

TEST_CASE("the neighbour lists are Ready's through VTK, for every cell type and kind", "[mesh]") {
    const auto expected = nlohmann::json::parse(testkit::slurp(fixtures / "expected.json"));
    REQUIRE(expected.size() >= 10);
    for (const auto& [name, lists] : expected.items()) {
        const ready::vtu::UnstructuredGrid g = ready::vtu::read_vtu(testkit::slurp(fixtures / (name + ".vtu")));
        for (const auto& [kind_name, kind] : kinds) {
            INFO(name << " " << kind_name);
            check_against(sim::mesh::neighbours(g.mesh, kind), lists[kind_name]);
        }
    }
}

TEST_CASE("neighbours are padded and weighted as Ready does", "[mesh]") {
    // Two triangles sharing the edge 1-2, and one alone.
    const Mesh m = mesh_of({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 5, 5, 0, 6, 5, 0, 5, 6, 0},
                           {{0, 1, 2}, {1, 3, 2}, {4, 5, 6}}, sim::mesh::cell_type::polygon);
    const Neighbours edge = sim::mesh::neighbours(m, Kind::edge);
    CHECK(edge.max_neighbors == 1);
    CHECK(edge.indices == std::vector<int>{1, 0, 2});  // the lone cell: itself,
    CHECK(edge.weights == std::vector<float>{1.0f, 1.0f, 0.0f});  // weighted 0
    // A 2-D cell has no faces: every slot is padding, and there is one.
    const Neighbours face = sim::mesh::neighbours(m, Kind::face);
    CHECK(face.max_neighbors == 1);
    CHECK(face.indices == std::vector<int>{0, 1, 2});
    CHECK(face.weights == std::vector<float>{0.0f, 0.0f, 0.0f});
    // Weights 1.0f / N, as float, and the padding after them.
    const Mesh fan = mesh_of({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0},
                             {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}, sim::mesh::cell_type::polygon);
    const Neighbours vertex = sim::mesh::neighbours(fan, Kind::vertex);
    REQUIRE(vertex.max_neighbors == 2);
    // Cell 1 reaches 2 only after the ring from 0 stops (0 and 2 share no edge).
    CHECK(vertex.indices == std::vector<int>{1, 2, 0, 2, 0, 1});
    CHECK(vertex.weights == std::vector<float>{0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f});
    const Neighbours fan_edges = sim::mesh::neighbours(fan, Kind::edge);
    CHECK(fan_edges.indices == std::vector<int>{1, 0, 0, 2, 1, 2});
    CHECK(fan_edges.weights == std::vector<float>{1.0f, 0.0f, 0.5f, 0.5f, 1.0f, 0.0f});
    // No cells: no slots.
    CHECK(sim::mesh::neighbours(Mesh{}, Kind::vertex).max_neighbors == 0);
}

TEST_CASE("meshes Ready cannot run are refused", "[mesh]") {
    Mesh mixed = mesh_of({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, {{0, 1, 2}, {1, 3, 2}}, sim::mesh::cell_type::polygon);
    mixed.types[1] = sim::mesh::cell_type::triangle;
    CHECK_THROWS_WITH(sim::mesh::neighbours(mixed, Kind::edge), Catch::Contains("more than one type"));
    Mesh outside = mesh_of({0, 0, 0, 1, 0, 0, 0, 1, 0}, {{0, 1, 3}}, sim::mesh::cell_type::triangle);
    CHECK_THROWS_WITH(sim::mesh::neighbours(outside, Kind::edge), Catch::Contains("a point index is 3, outside the 3 points"));
    Mesh short_offsets = mesh_of({0, 0, 0, 1, 0, 0, 0, 1, 0}, {{0, 1, 2}}, sim::mesh::cell_type::triangle);
    short_offsets.offsets.pop_back();
    CHECK_THROWS_AS(sim::mesh::neighbours(short_offsets, Kind::edge), std::invalid_argument);
}

TEST_CASE("a mesh whose cells crowd round one point is refused before its neighbours are searched", "[mesh][bounds]") {
    // A fan of n triangles round point 0: each cell's points pool about n
    // cells, so the search would cost about n^3 (n = 20,000: 8e12).
    const auto fan = [](int n) {
        std::vector<double> points = {0, 0, 0};
        std::vector<std::vector<std::int64_t>> cells;
        for (int k = 0; k <= n; ++k) {
            const double a = 2 * M_PI * k / (n + 1);
            points.insert(points.end(), {std::cos(a), std::sin(a), 0});
        }
        for (int k = 0; k < n; ++k) cells.push_back({0, 1 + k, 2 + k});
        return mesh_of(points, cells, sim::mesh::cell_type::triangle);
    };
    CHECK_THROWS_WITH(sim::mesh::neighbours(fan(20000), Kind::vertex),
                      Catch::Contains("finding their neighbours would take 8e+12 steps; figgen takes at most 4e+09"));
    CHECK_THROWS_WITH(sim::mesh::neighbours(fan(20000), Kind::edge), Catch::Contains("figgen takes at most 4e+09"));
    // A small fan is served: every cell a neighbour of every other by vertex.
    const Neighbours small = sim::mesh::neighbours(fan(200), Kind::vertex);
    CHECK(small.max_neighbors == 199);
}

TEST_CASE("the mesh Laplacian is Ready's kernel, in its order and rounding", "[mesh]") {
    const ready::vtu::UnstructuredGrid g = ready::vtu::read_vtu(testkit::slurp(fixtures / "bunny.vtu"));
    const Neighbours n = sim::mesh::neighbours(g.mesh, Kind::vertex);
    // Values whose sums round differently in different orders.
    std::vector<float> x(g.mesh.cell_count());
    for (std::size_t i = 0; i < x.size(); ++i)
        x[i] = static_cast<float>(std::ldexp(1.0 + 0.37 * static_cast<double>(i % 7), static_cast<int>(i % 5) * 6 - 12));
    for (const bool fused : {false, true}) {
        const std::vector<float> l = sim::mesh::laplacian(n, x, fused);
        for (std::size_t i = 0; i < x.size(); ++i) REQUIRE(l[i] == kernel_laplacian(n, x, i, fused));
    }
    // The order matters to the bits (which is why the lists are Ready's), and so does the contraction.
    Neighbours reversed = n;
    const auto slots = static_cast<std::size_t>(n.max_neighbors);
    for (std::size_t c = 0; c < x.size(); ++c) {
        std::size_t real = 0;
        while (real < slots && n.weights[c * slots + real] > 0) ++real;
        std::reverse(reversed.indices.begin() + static_cast<std::ptrdiff_t>(c * slots),
                     reversed.indices.begin() + static_cast<std::ptrdiff_t>(c * slots + real));
    }
    CHECK(sim::mesh::laplacian(reversed, x, false) != sim::mesh::laplacian(n, x, false));
    CHECK(sim::mesh::laplacian(n, x, true) != sim::mesh::laplacian(n, x, false));
    // Doubles take the float weights widened.
    const std::vector<double> xd(x.begin(), x.end());
    const std::vector<double> ld = sim::mesh::laplacian(n, xd, false);
    double sum = -xd[0];
    for (std::size_t k = 0; k < slots; ++k) sum += xd[static_cast<std::size_t>(n.indices[k])] * static_cast<double>(n.weights[k]);
    CHECK(ld[0] == sum * 4.0);
    // The padding is read too, as Ready's kernel reads it: an infinite
    // cell with padding makes its own Laplacian NaN (inf * 0).
    std::size_t padded = 0;
    while (padded < x.size() && n.weights[padded * slots + slots - 1] > 0) ++padded;
    REQUIRE(padded < x.size());
    std::vector<float> inf = x;
    inf[padded] = std::numeric_limits<float>::infinity();
    CHECK(std::isnan(sim::mesh::laplacian(n, inf, false)[padded]));
    CHECK_THROWS_AS(sim::mesh::laplacian(n, std::vector<float>(3), false), std::invalid_argument);
}

// Every mesh of Ready's Patterns folder, each kind, against VTK: about a
// minute. FIGGEN_READY_PATTERNS=/path/to/Ready/Patterns figgen_tests '[mesh-ready]'
TEST_CASE("the neighbour lists of Ready's own meshes are VTK's", "[.][mesh-ready]") {
    const char* patterns = std::getenv("FIGGEN_READY_PATTERNS");
    if (!patterns) {
        WARN("FIGGEN_READY_PATTERNS is not set: Ready's meshes are not checked");
        return;
    }
    const fs::path out = testkit::fresh_dir("mesh-ready");
    int meshes = 0;
    for (const auto& entry : fs::recursive_directory_iterator(patterns)) {
        if (entry.path().extension() != ".vtu") continue;
        ++meshes;
        const ready::vtu::UnstructuredGrid g = ready::vtu::read_vtu(testkit::slurp(entry.path()));
        for (const auto& [kind_name, kind] : kinds) {
            INFO(entry.path().string() << " " << kind_name);
            const fs::path json = out / (std::to_string(meshes) + "." + kind_name + ".json");
            const auto vtk = testkit::run_command("/usr/bin/python3 " + (fixtures / "ready_neighbours.py").string() + " '" +
                                                  entry.path().string() + "' " + kind_name + " " + json.string());
            INFO(vtk.output);
            REQUIRE(vtk.status == 0);
            check_against(sim::mesh::neighbours(g.mesh, kind), nlohmann::json::parse(testkit::slurp(json)));
        }
    }
    CHECK(meshes > 0);
}
