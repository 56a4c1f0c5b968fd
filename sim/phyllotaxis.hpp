#pragma once
// Vogel's model of the sunflower head (1979): seed n sits at radius
// spacing * sqrt(n) and angle n * divergence, so each seed claims the same
// area and, at the golden angle 137.508 degrees, no spiral arm ever lines up.

#include <vector>

#include <glm/glm.hpp>

namespace sim {

struct PhyllotaxisParams {
    int seeds = 240;                  // seeds placed, n = 0 .. seeds-1, 1..100000
    double divergence = 137.508;      // degrees turned from one seed to the next, (0, 360)
    double spacing = 7;               // radius of seed n is spacing * sqrt(n), > 0

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

struct Seed {
    int n;                  // order of placement
    glm::dvec2 position;    // x right, y up, the centre at (0, 0)
    double angle;           // n * divergence in radians (unreduced, as the article's theta)
};

std::vector<Seed> vogel_spiral(const PhyllotaxisParams& params);

}  // namespace sim
