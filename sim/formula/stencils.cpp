#include "sim/formula/stencils.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>

namespace sim::formula {

namespace {

// Ready builds each stencil from an array of weights: a row (one axis), a
// square in reading order (the first row the northmost, y + half), or a
// cube of such squares from its lowest plane (z - half) up.
using Row = std::vector<int>;
using Square = std::vector<Row>;
using Cube = std::vector<Square>;

Stencil from_row(const std::string& label, const Row& weights, int divisor, int dx_power, int axis) {
    Stencil s{label, {}, divisor, dx_power};
    const int half = static_cast<int>(weights.size() - 1) / 2;
    for (int i = 0; i < static_cast<int>(weights.size()); ++i)
        if (weights[i] != 0) {
            int offset[3] = {0, 0, 0};
            offset[axis] = i - half;
            s.points.push_back({offset[0], offset[1], offset[2], weights[i]});
        }
    return s;
}

Stencil from_cube(const std::string& label, const Cube& planes, int divisor, int dx_power) {
    Stencil s{label, {}, divisor, dx_power};
    const int l = static_cast<int>(planes.size());
    for (int k = 0; k < l; ++k) {
        const int m = static_cast<int>(planes[k].size());
        for (int j = 0; j < m; ++j) {
            const int n = static_cast<int>(planes[k][j].size());
            for (int i = 0; i < n; ++i)
                if (planes[k][j][i] != 0)
                    s.points.push_back({i - (n - 1) / 2, -j + (m - 1) / 2, k - (l - 1) / 2, planes[k][j][i]});
        }
    }
    return s;
}

Stencil from_square(const std::string& label, const Square& rows, int divisor, int dx_power) {
    return from_cube(label, {rows}, divisor, dx_power);
}

Square symmetric_3x3(int c1, int c2, int c3) {
    return {{c1, c2, c1}, {c2, c3, c2}, {c1, c2, c1}};
}

Cube symmetric_3x3x3(int c1, int c2, int c3, int c4) {
    return {symmetric_3x3(c1, c2, c3), symmetric_3x3(c2, c3, c4), symmetric_3x3(c1, c2, c3)};
}

Square symmetric_5x5(int c1, int c2, int c3, int c4, int c5, int c6) {
    return {{c1, c2, c3, c2, c1}, {c2, c4, c5, c4, c2}, {c3, c5, c6, c5, c3}, {c2, c4, c5, c4, c2}, {c1, c2, c3, c2, c1}};
}

// Ready's RotationallySymmetric5x5x5: ten weights by the point's place.
Cube symmetric_5x5x5(int c1, int c2, int c3, int c4, int c5, int c6, int c7, int c8, int c9, int c10) {
    const Square outer = symmetric_5x5(c1, c2, c3, c4, c5, c8);
    const Square inner = symmetric_5x5(c2, c4, c5, c6, c7, c9);
    const Square middle = symmetric_5x5(c3, c5, c8, c7, c9, c10);
    return {outer, inner, middle, inner, outer};
}

// A 7 x 7 x 7 stencil whose weight depends only on the point's distances
// along the three axes, whatever their order: weight[a][b][c] for sorted
// distances a <= b <= c (the other entries unused).
Cube fully_symmetric_7(const int (&weight)[4][4][4]) {
    Cube cube(7, Square(7, Row(7, 0)));
    for (int k = 0; k < 7; ++k)
        for (int j = 0; j < 7; ++j)
            for (int i = 0; i < 7; ++i) {
                std::array<int, 3> d = {std::abs(i - 3), std::abs(j - 3), std::abs(k - 3)};
                std::sort(d.begin(), d.end());
                cube[k][j][i] = weight[d[0]][d[1]][d[2]];
            }
    return cube;
}

Stencil gaussian(int dimensions) {
    switch (dimensions) {
    case 1: return from_row("gaussian", {1, 4, 6, 4, 1}, 16, 0, 0);
    case 2: return from_square("gaussian", symmetric_5x5(1, 4, 7, 16, 26, 41), 273, 0);
    default: {
        // Ready's own cube (its Scripts/Python/convolve.py), rows and
        // columns as it gives them: not symmetric in x and y.
        const Square outer = {{1, 4, 6, 4, 1}, {4, 16, 25, 16, 4}, {7, 27, 44, 27, 7}, {4, 16, 25, 16, 4}, {1, 4, 6, 4, 1}};
        const Square inner = {{4, 16, 25, 16, 4},
                              {16, 62, 101, 62, 16},
                              {26, 101, 164, 101, 26},
                              {16, 62, 101, 62, 16},
                              {4, 16, 25, 16, 4}};
        const Square middle = {{7, 27, 44, 27, 7},
                               {26, 101, 164, 101, 26},
                               {41, 159, 258, 159, 41},
                               {26, 101, 164, 101, 26},
                               {7, 27, 44, 27, 7}};
        return from_cube("gaussian", {outer, inner, middle, inner, outer}, 4390, 0);
    }
    }
}

// Patra and Karttunen (2006), "Stencils with isotropic discretization
// error for differential operators", as Ready cites them in 2-D and 3-D.
Stencil laplacian(int dimensions, Accuracy accuracy) {
    switch (dimensions) {
    case 1:
        if (accuracy == Accuracy::high) return from_row("laplacian", {-1, 16, -30, 16, -1}, 12, 2, 0);
        return from_row("laplacian", {1, -2, 1}, 1, 2, 0);
    case 2:
        switch (accuracy) {
        case Accuracy::low: return from_square("laplacian", symmetric_3x3(0, 1, -4), 1, 2);
        case Accuracy::medium: return from_square("laplacian", symmetric_3x3(1, 4, -20), 6, 2);
        case Accuracy::high: return from_square("laplacian", symmetric_5x5(0, -2, -1, 16, 52, -252), 60, 2);
        }
        break;
    default: break;
    }
    return from_cube("laplacian", symmetric_3x3x3(1, 3, 14, -128), 30, 2);  // 3-D, at every accuracy
}

Stencil bilaplacian(int dimensions) {
    switch (dimensions) {
    case 1: return from_row("bilaplacian", {1, -4, 6, -4, 1}, 1, 4, 0);
    case 2: return from_square("bilaplacian", symmetric_5x5(0, 1, 1, -2, -10, 36), 3, 4);
    default: return from_cube("bilaplacian", symmetric_5x5x5(-1, 0, 0, 10, 0, -20, -36, 0, 0, 360), 36, 4);
    }
}

Stencil trilaplacian(int dimensions) {
    switch (dimensions) {
    case 1: return from_row("trilaplacian", {1, -6, 15, -20, 15, -6, 1}, 1, 6, 0);
    case 2:
        return from_square("trilaplacian",
                           {{0, 1, 5, 6, 5, 1, 0},
                            {1, 6, -33, -56, -33, 6, 1},
                            {5, -33, 6, 314, 6, -33, 5},
                            {6, -56, 314, -888, 314, -56, 6},
                            {5, -33, 6, 314, 6, -33, 5},
                            {1, 6, -33, -56, -33, 6, 1},
                            {0, 1, 5, 6, 5, 1, 0}},
                           18, 6);
    default: {
        // Ready's 7 x 7 x 7 cube (a 3-D laplacian convolved with its
        // bilaplacian), by the point's sorted distances along the axes.
        static const int weight[4][4][4] = {
            {{-47536, 2680, -392, 40}, {0, 4816, -396, 60}, {0, 0, -28, 20}, {0, 0, 0, 0}},
            {{0, 0, 0, 0}, {0, 1827, -1719, 139}, {0, 0, 180, 27}, {0, 0, 0, -1}},
            {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 198, -4}, {0, 0, 0, -3}},
            {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, -1}},
        };
        return from_cube("trilaplacian", fully_symmetric_7(weight), 1080, 6);
    }
    }
}

}  // namespace

std::vector<Stencil> ready_stencils(Accuracy accuracy, int dimensions) {
    if (dimensions < 1 || dimensions > 3)
        throw std::invalid_argument("a grid of " + std::to_string(dimensions) +
                                    " dimensions: Ready's stencils are for 1, 2 or 3");
    const bool high = accuracy == Accuracy::high;
    std::vector<Stencil> s;
    const char* axes[3] = {"x", "y", "z"};
    // Second order, or fourth at high accuracy: x_gradient, y_gradient,
    // z_gradient, then the second and third derivatives.
    struct Derivative {
        const char* name;
        Row medium, high;
        int divisor_medium, divisor_high, dx_power;
    };
    const Derivative derivatives[] = {
        {"_gradient", {-1, 0, 1}, {1, -8, 0, 8, -1}, 2, 12, 1},
        {"_deriv2", {1, -2, 1}, {-1, 16, -30, 16, -1}, 1, 12, 2},
        {"_deriv3", {-1, 2, 0, -2, 1}, {1, -8, 13, 0, -13, 8, -1}, 2, 8, 3},
    };
    for (const Derivative& d : derivatives)
        for (int axis = 0; axis < 3; ++axis)
            s.push_back(from_row(axes[axis] + std::string(d.name), high ? d.high : d.medium,
                                 high ? d.divisor_high : d.divisor_medium, d.dx_power, axis));
    s.push_back(gaussian(dimensions));
    s.push_back(laplacian(dimensions, accuracy));
    s.push_back(bilaplacian(dimensions));
    s.push_back(trilaplacian(dimensions));
    s.push_back(from_square("sobelN", {{1, 2, 1}, {0, 0, 0}, {-1, -2, -1}}, 1, 0));
    s.push_back(from_square("sobelS", {{-1, -2, -1}, {0, 0, 0}, {1, 2, 1}}, 1, 0));
    s.push_back(from_square("sobelE", {{-1, 0, 1}, {-2, 0, 2}, {-1, 0, 1}}, 1, 0));
    s.push_back(from_square("sobelW", {{1, 0, -1}, {2, 0, -2}, {1, 0, -1}}, 1, 0));
    s.push_back(from_square("sobelNW", {{2, 1, 0}, {1, 0, -1}, {0, -1, -2}}, 1, 0));
    s.push_back(from_square("sobelNE", {{0, 1, 2}, {-1, 0, 1}, {-2, -1, 0}}, 1, 0));
    s.push_back(from_square("sobelSW", {{0, -1, -2}, {1, 0, -1}, {2, 1, 0}}, 1, 0));
    s.push_back(from_square("sobelSE", {{-2, -1, 0}, {-1, 0, 1}, {0, 1, 2}}, 1, 0));
    return s;
}

const std::vector<std::string>& stencil_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const Stencil& s : ready_stencils(Accuracy::medium, 2)) n.push_back(s.label);
        n.push_back("gradient_mag_squared");
        return n;
    }();
    return names;
}

}  // namespace sim::formula
