// The isosurface of a 3-D field (render/isosurface.hpp) against geometry:
// a sphere's surface lies at its radius, its normals point out, its area is
// 4 pi r^2, it is closed (every edge shared by two facets), and it has as
// many facets as Euler's formula gives a sphere with a corner on each
// crossed edge of the grid.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>
#include <string>
#include <vector>
#if defined(_OPENMP)
#include <omp.h>
#endif

#include "render/isosurface.hpp"

namespace {

// r - |p - c| on an n^3 grid: above 0 inside a ball of radius r.
std::vector<double> ball(int n, double r, glm::dvec3 c) {
    std::vector<double> v(static_cast<std::size_t>(n) * n * n);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                v[(static_cast<std::size_t>(z) * n + y) * n + x] = r - glm::length(glm::dvec3(x, y, z) - c);
    return v;
}

}  // namespace

TEST_CASE("a ball's isosurface is a closed sphere of its radius, its normals outward", "[isosurface]") {
    const int n = 32;
    const double r = 10;
    const glm::dvec3 c(15.3, 16.1, 15.7);
    const std::vector<double> v = ball(n, r, c);
    const std::vector<render::Facet> facets = render::isosurface({n, n, n, v}, 0.0, {1, 1, 1, 1});
    REQUIRE(facets.size() > 1000);
    double area = 0;
    // Each edge, by its corners' positions in order, and how many facets hold it.
    std::map<std::tuple<float, float, float, float, float, float>, int> edges;
    for (const render::Facet& f : facets) {
        for (const glm::vec3* p : {&f.a, &f.b, &f.c}) REQUIRE(std::abs(glm::length(glm::dvec3(*p) - c) - r) < 0.1);
        // Wound so that its front faces out, as its normals do.
        const glm::vec3 across = glm::cross(f.b - f.a, f.c - f.a);
        const glm::vec3 centre = (f.a + f.b + f.c) / 3.0f;
        CHECK(glm::dot(across, centre - glm::vec3(c)) >= 0);
        for (const glm::vec3* normal : {&f.na, &f.nb, &f.nc})
            CHECK(glm::dot(glm::normalize(*normal), glm::normalize(centre - glm::vec3(c))) > 0.95);
        area += 0.5 * glm::length(across);
        const glm::vec3 corner[3] = {f.a, f.b, f.c};
        for (int k = 0; k < 3; ++k) {
            glm::vec3 p = corner[k], q = corner[(k + 1) % 3];
            if (std::tie(q.x, q.y, q.z) < std::tie(p.x, p.y, p.z)) std::swap(p, q);
            ++edges[{p.x, p.y, p.z, q.x, q.y, q.z}];
        }
    }
    CHECK(area == Approx(4 * std::numbers::pi * r * r).epsilon(0.02));
    int open = 0;
    for (const auto& [edge, count] : edges) open += count != 2;
    CHECK(open == 0);
    // One corner a crossed edge of the grid, and a closed surface of a
    // sphere's topology: V - E + F = 2 with E = 3F / 2, so F = 2V - 4.
    long long crossed = 0;
    auto above = [&](int x, int y, int z) { return v[(static_cast<std::size_t>(z) * n + y) * n + x] > 0; };
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                if (x + 1 < n) crossed += above(x, y, z) != above(x + 1, y, z);
                if (y + 1 < n) crossed += above(x, y, z) != above(x, y + 1, z);
                if (z + 1 < n) crossed += above(x, y, z) != above(x, y, z + 1);
            }
    CHECK(static_cast<long long>(facets.size()) == 2 * crossed - 4);
}

TEST_CASE("a field all below the level has no isosurface, all above it is the capped box, a coarser one has fewer facets", "[isosurface]") {
    const int n = 24;
    const std::vector<double> v = ball(n, 8, {11.5, 11.5, 11.5});
    CHECK(render::isosurface({n, n, n, v}, 100.0, {1, 1, 1, 1}).empty());
    render::IsosurfaceGrid open{n, n, n, v};
    open.capped = false;
    CHECK(render::isosurface(open, -100.0, {1, 1, 1, 1}).empty());
    // All above the level and capped: the grid's box.
    double box = 0;
    for (const render::Facet& f : render::isosurface({n, n, n, v}, -100.0, {1, 1, 1, 1}))
        box += 0.5 * glm::length(glm::cross(f.b - f.a, f.c - f.a));
    CHECK(box == Approx(6.0 * (n - 1) * (n - 1)));
    const auto fine = render::isosurface({n, n, n, v}, 0.0, {1, 1, 1, 1});
    int stride = 0;
    const auto coarse = render::isosurface_within({n, n, n, v}, 0.0, {1, 1, 1, 1}, static_cast<long long>(fine.size() / 2), &stride);
    CHECK(stride >= 2);
    CHECK(coarse.size() <= fine.size() / 2);
    CHECK(!coarse.empty());
    CHECK_THROWS_AS(render::isosurface({n, n, n, std::span<const double>(v).first(10)}, 0.0, {1, 1, 1, 1}),
                    std::invalid_argument);
    CHECK_THROWS_AS(render::isosurface({n, n, n, v}, std::nan(""), {1, 1, 1, 1}), std::invalid_argument);
}

TEST_CASE("where the region meets the grid's faces, caps close it", "[isosurface]") {
    // x - 10.5 above 0: the slab 10.5 <= x <= 23 of a 24^3 grid (cells 0 .. 23).
    const int n = 24;
    std::vector<double> v(static_cast<std::size_t>(n) * n * n);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<double>(i % n) - 10.5;
    auto area = [](const std::vector<render::Facet>& facets) {
        double sum = 0;
        for (const render::Facet& f : facets) sum += 0.5 * glm::length(glm::cross(f.b - f.a, f.c - f.a));
        return sum;
    };
    render::IsosurfaceGrid grid{n, n, n, v};
    grid.capped = false;
    CHECK(area(render::isosurface(grid, 0.0, {1, 1, 1, 1})) == Approx(23.0 * 23.0));
    grid.capped = true;
    const auto closed = render::isosurface(grid, 0.0, {1, 1, 1, 1});
    // The plane, the far face, and four sides of 12.5 x 23.
    CHECK(area(closed) == Approx(2 * 23.0 * 23.0 + 4 * 12.5 * 23.0));
    // Every facet faces out of the slab.
    for (const render::Facet& f : closed) {
        const glm::vec3 across = glm::cross(f.b - f.a, f.c - f.a);
        if (glm::length(across) == 0) continue;
        const glm::vec3 centre = (f.a + f.b + f.c) / 3.0f;
        CHECK(glm::dot(across, centre - glm::vec3(16.75f, 11.5f, 11.5f)) > 0);
    }
}

TEST_CASE("the region below the level is closed the same way, its normals out of it", "[isosurface]") {
    // The ball as the values below the level of its negation.
    const int n = 24;
    std::vector<double> v(static_cast<std::size_t>(n) * n * n);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                v[(static_cast<std::size_t>(z) * n + y) * n + x] = glm::length(glm::dvec3(x, y, z) - glm::dvec3(11.5)) - 8;
    render::IsosurfaceGrid grid{n, n, n, v};
    grid.inside_below = true;
    const auto facets = render::isosurface(grid, 0.0, {1, 1, 1, 1});
    REQUIRE(!facets.empty());
    for (const render::Facet& f : facets) {
        const glm::vec3 centre = (f.a + f.b + f.c) / 3.0f - glm::vec3(11.5f);
        CHECK(glm::dot(glm::cross(f.b - f.a, f.c - f.a), centre) >= 0);
        CHECK(glm::dot(f.na, centre) > 0);
    }
}

TEST_CASE("the layers walked side by side give the facets of one walk, in its order", "[isosurface]") {
    // Two balls and the capped faces: facets in many layers. One thread
    // walks the layers in turn; several take them side by side.
    const int n = 40;
    std::vector<double> v = ball(n, 9, {12.5, 14.5, 13.5});
    const std::vector<double> other = ball(n, 7, {27.5, 25.5, 28.5});
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::max(v[i], other[i]);
    auto bits = [](const std::vector<render::Facet>& facets) {
        return std::string(reinterpret_cast<const char*>(facets.data()), facets.size() * sizeof(render::Facet));
    };
#if defined(_OPENMP)
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const auto one = render::isosurface({n, n, n, v}, 0.0, {1, 1, 1, 1});
    omp_set_num_threads(4);
    const auto four = render::isosurface({n, n, n, v}, 0.0, {1, 1, 1, 1});
    omp_set_num_threads(threads);
#else
    const auto one = render::isosurface({n, n, n, v}, 0.0, {1, 1, 1, 1});
    const auto four = render::isosurface({n, n, n, v}, 0.0, {1, 1, 1, 1});
#endif
    REQUIRE(one.size() > 1000);
    CHECK(bits(one) == bits(four));
    // The budget holds as it did: at most `most` facets, else a coarser walk.
    int stride = 0;
    const auto within = render::isosurface_within({n, n, n, v}, 0.0, {1, 1, 1, 1}, static_cast<long long>(one.size()), &stride);
    CHECK(stride == 1);
    CHECK(bits(within) == bits(one));
    const auto fewer = render::isosurface_within({n, n, n, v}, 0.0, {1, 1, 1, 1}, static_cast<long long>(one.size()) - 1, &stride);
    CHECK(stride == 2);
    CHECK(fewer.size() < one.size());
}
