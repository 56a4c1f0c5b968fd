#pragma once
// Iterated function systems drawn by the chaos game (Barnsley, "Fractals
// Everywhere", 1988): a point jumps through a set of contracting affine maps,
// each picked at random with its own probability; after a few jumps it is
// within rounding of the attractor and every later point lies on it.
//
// Randomness: one rng.uniform() per step, discarded steps included, which
// picks the map by cumulative probability in the maps' fixed order. The
// stream therefore does not depend on the coordinates.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "sim/random.hpp"

namespace sim {

struct AffineMap {
    double a, b, c, d;  // linear part: x' = a x + b y + e, y' = c x + d y + f
    double e, f;        // translation
    double p;           // probability that a step applies this map, >= 0

    glm::dvec2 apply(glm::dvec2 v) const { return {a * v.x + b * v.y + e, c * v.x + d * v.y + f}; }
};

struct Ifs {
    std::vector<AffineMap> maps;  // 1..64 maps, finite coefficients, probabilities summing to 1 within 1e-9

    void validate() const;  // throws std::invalid_argument naming the bad map, coefficient or sum
};

// The fern of Barnsley (1988), with the catalog's four maps: stem, the
// successively smaller leaflets, the lowest left leaflet, the lowest right.
Ifs barnsley_fern();

struct ChaosGameParams {
    std::uint64_t points = 200000;  // points returned, 0..100,000,000
    std::uint64_t discard = 100;    // steps run first and dropped, 0..100,000,000 (start may lie off the attractor)
    glm::dvec2 start{0, 0};         // the first point, before any step; finite

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

// The index of the map a uniform u in [0, 1) picks: the first whose
// cumulative probability exceeds u. A map with p = 0 is never picked; when
// rounding leaves the total a hair below 1 and u above it, the last map with
// p > 0 is picked.
std::size_t pick_map(const Ifs& ifs, double u);

// Runs the chaos game for discard + points steps and returns the last
// `points` points, in order. When map_counts is given it is resized to the
// number of maps and counts how often each map was picked over every step,
// discarded ones included. Validates both arguments.
std::vector<glm::dvec2> chaos_game(const Ifs& ifs, const ChaosGameParams& params, Random& rng,
                                   std::vector<std::uint64_t>* map_counts = nullptr);

// Points per pixel over the box [lo, hi] (edges included): a height x width
// image stored row by row, row 0 at the top (y near hi.y) as render/field
// draws it, column 0 at the left (x near lo.x). Points outside the box are
// not counted.
struct Density {
    int width, height;                  // pixels across and down
    glm::dvec2 lo, hi;                  // the box: lower-left and upper-right corners
    std::vector<std::uint32_t> counts;  // width * height counts, row-major from the top row

    std::uint32_t at(int row, int col) const { return counts[static_cast<std::size_t>(row) * width + col]; }
};

// width and height 1..16384; lo and hi finite with lo < hi on both axes.
Density density(const std::vector<glm::dvec2>& points, int width, int height, glm::dvec2 lo, glm::dvec2 hi);

}  // namespace sim
