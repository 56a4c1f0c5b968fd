#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "sim/cell1d.hpp"
#include "sim/fractal.hpp"

using sim::Cell1D;
using sim::Cell1DParams;

namespace {

Cell1D run(int rule, int rows, int width = 0, sim::Boundary boundary = sim::Boundary::zero) {
    Cell1D ca(Cell1DParams{rule, rows, width, boundary});
    while (ca.rows_filled() < rows) ca.step();
    return ca;
}

long row_sum(const Cell1D& ca, int row) {
    long sum = 0;
    for (int j = 0; j < ca.cells().cols(); ++j) sum += ca.cells()(row, j);
    return sum;
}

}  // namespace

TEST_CASE("cell1d starts with one on cell in the middle of row 0", "[cell1d]") {
    Cell1D ca(Cell1DParams{18, 32, 0, sim::Boundary::zero});
    CHECK(ca.cells().rows() == 32);
    CHECK(ca.cells().cols() == 65);  // 2 * 32 + 1
    CHECK(ca.cells()(0, 32) == 1);
    CHECK(ca.on_cells() == 1);
    CHECK(ca.rows_filled() == 1);
    Cell1D narrow(Cell1DParams{18, 5, 4, sim::Boundary::zero});
    CHECK(narrow.cells()(0, 2) == 1);  // width / 2
}

TEST_CASE("rule 18 from one cell has 3 to the k on cells in its first 2 to the k rows", "[cell1d]") {
    // Rule 18 grows Pascal's triangle mod 2, whose first 2^k rows are three
    // copies of the first 2^(k-1) rows (Sierpinski): N(2^k) = 3 N(2^(k-1)), N(1) = 1.
    const Cell1D ca = run(18, 512);
    std::vector<long> total_after(513, 0);  // total_after[r]: on cells in rows 0 .. r - 1
    for (int r = 0; r < 512; ++r) total_after[r + 1] = total_after[r] + row_sum(ca, r);
    long power_of_three = 1;
    for (int k = 0; k <= 9; ++k) {
        INFO("k = " << k);
        CHECK(total_after[std::size_t{1} << k] == power_of_three);
        power_of_three *= 3;
    }
    CHECK(ca.on_cells() == 19683);  // 3^9 on cells in 2^9 = 512 rows
}

TEST_CASE("rule 90 and rule 18 from one cell equal Pascal's triangle mod 2", "[cell1d]") {
    // Row i holds C(i, k) mod 2 at column centre - i + 2k and 0 elsewhere.
    // Lucas's theorem: C(i, k) is odd exactly when the bits of k are a subset of those of i.
    const int rows = 100, centre = rows;
    for (int rule : {90, 18}) {
        const Cell1D ca = run(rule, rows);
        for (int i = 0; i < rows; ++i)
            for (int j = 0; j < ca.cells().cols(); ++j) {
                const int offset = j - (centre - i);
                int expected = 0;
                if (offset >= 0 && offset <= 2 * i && offset % 2 == 0) {
                    const int k = offset / 2;
                    expected = (k & i) == k ? 1 : 0;
                }
                INFO("rule " << rule << " row " << i << " column " << j);
                REQUIRE(ca.cells()(i, j) == expected);
            }
    }
}

TEST_CASE("rule 50 has i plus 1 on cells in row i", "[cell1d]") {
    const int rows = 200;
    const Cell1D ca = run(50, rows);
    for (int i = 0; i < rows; ++i) REQUIRE(row_sum(ca, i) == i + 1);
    CHECK(ca.on_cells() == long{rows} * (rows + 1) / 2);  // (i + 1)(i + 2) / 2 with i = rows - 1
    const std::vector<long> counts = sim::count_cells(50, rows, sim::Boundary::zero);
    for (int i = 1; i < rows; ++i) REQUIRE(counts[i - 1] == long{i} * (i + 1) / 2);
}

TEST_CASE("rule 0 dies after the first row", "[cell1d]") {
    const Cell1D ca = run(0, 20);
    CHECK(ca.on_cells() == 1);
    for (int i = 1; i < 20; ++i) CHECK(row_sum(ca, i) == 0);
}

TEST_CASE("rule 255 turns every cell on after row 0 even at the zero-filled ends", "[cell1d]") {
    // Every neighbourhood, also 000 beyond the ends, maps to 1.
    const Cell1D ca = run(255, 10, 7);
    for (int i = 1; i < 10; ++i) CHECK(row_sum(ca, i) == 7);
    CHECK(ca.on_cells() == 1 + 9 * 7);
}

TEST_CASE("rule 1 turns on only the all-off neighbourhood also at the zero-filled ends", "[cell1d]") {
    // Rule 1 turns on only 000. Row 1: all on but the three cells next to
    // the seed. Row 2: interior cells see 111 (off), and the end cells see
    // 0 beyond the edge then 11, which is 3 (off) too, so row 2 is off
    // except the cells whose neighbourhood touches row 1's gap of zeros.
    const Cell1D ca = run(1, 3, 11);
    const std::vector<int> row1 = {1, 1, 1, 1, 0, 0, 0, 1, 1, 1, 1};
    for (int j = 0; j < 11; ++j) CHECK(ca.cells()(1, j) == row1[j]);
    // Row 2: on where left, centre and right of row 1 are all 0: only column 5.
    for (int j = 0; j < 11; ++j) CHECK(ca.cells()(2, j) == (j == 5 ? 1 : 0));
    // With wrap the ends see each other: row 1 is the same, but the end
    // cells of row 2 see 1 beyond the edge and stay off as well.
    const Cell1D wrapped = run(1, 3, 11, sim::Boundary::wrap);
    CHECK(wrapped.cells() == ca.cells());
}

TEST_CASE("wrap and zero ends agree until the pattern reaches the edge", "[cell1d]") {
    // Width 21, seed at column 10: the light cone touches column 0 at row
    // 10, so row 11 is the first that can differ. Rule 30 keeps both cone
    // edges on, and column 0 of row 11 reads (0,1,x) -> on with zero ends
    // but (1,1,x) -> off when wrapping.
    const Cell1D zero = run(30, 40, 21, sim::Boundary::zero);
    const Cell1D wrap = run(30, 40, 21, sim::Boundary::wrap);
    for (int i = 0; i <= 10; ++i)
        for (int j = 0; j < 21; ++j) REQUIRE(zero.cells()(i, j) == wrap.cells()(i, j));
    CHECK(zero.cells()(10, 0) == 1);
    CHECK(zero.cells()(10, 20) == 1);
    CHECK(zero.cells()(11, 0) == 1);
    CHECK(wrap.cells()(11, 0) == 0);
    CHECK(zero.cells() != wrap.cells());
}

TEST_CASE("count_cells starts at 1 and gives n minus 1 running totals", "[cell1d]") {
    const std::vector<long> counts = sim::count_cells(18, 9, sim::Boundary::zero);
    REQUIRE(counts.size() == 8);
    // Rule 18 rows: 1, 2, 2, 4, 2, 4, 4, 8 on cells (Pascal mod 2 row sums are 2^popcount(i)).
    const std::vector<long> expected = {1, 3, 5, 9, 11, 15, 19, 27};
    CHECK(counts == expected);
    CHECK(sim::count_cells(18, 1, sim::Boundary::zero).empty());
}

TEST_CASE("count_cells log-log slopes match the book's 1.01 1.97 1.57 for rules 20 50 18", "[cell1d]") {
    const struct {
        int rule;
        double book;
    } cases[] = {{20, 1.01}, {50, 1.97}, {18, 1.57}};
    for (const auto& c : cases) {
        const std::vector<long> counts = sim::count_cells(c.rule, 500, sim::Boundary::zero);
        std::vector<double> steps, cells;
        for (std::size_t i = 0; i < counts.size(); ++i) {
            steps.push_back(static_cast<double>(i + 1));
            cells.push_back(static_cast<double>(counts[i]));
        }
        const sim::LineFit fit = sim::fit_log_log(steps, cells);
        INFO("rule " << c.rule << " slope " << fit.slope << " book " << c.book);
        CHECK(fit.points == 499);
        CHECK(fit.slope == Approx(c.book).margin(0.02));
    }
}

TEST_CASE("cell1d refuses to step past its last row", "[cell1d]") {
    Cell1D ca(Cell1DParams{18, 2, 0, sim::Boundary::zero});
    ca.step();
    CHECK(ca.rows_filled() == 2);
    CHECK_THROWS_AS(ca.step(), std::logic_error);
    Cell1D one(Cell1DParams{18, 1, 1, sim::Boundary::wrap});
    CHECK_THROWS_AS(one.step(), std::logic_error);
}

TEST_CASE("a one-cell wrapped row is its own left and right neighbour", "[cell1d]") {
    // Rule 128 turns on only 111: a lone on cell that wraps onto itself sees 111.
    const Cell1D wrapped = run(128, 4, 1, sim::Boundary::wrap);
    CHECK(wrapped.on_cells() == 4);
    const Cell1D zero = run(128, 4, 1, sim::Boundary::zero);  // sees 010: off
    CHECK(zero.on_cells() == 1);
}

TEST_CASE("cell1d parameters are validated with messages naming them", "[cell1d]") {
    auto message_of = [](Cell1DParams p) {
        try {
            p.validate();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(message_of(Cell1DParams{256, 32, 0, sim::Boundary::zero}) ==
          "rule = 256 is not allowed: an integer from 0 to 255");
    CHECK(message_of(Cell1DParams{18, 0, 0, sim::Boundary::zero}) ==
          "rows = 0 is not allowed: an integer from 1 to 100000");
    CHECK(message_of(Cell1DParams{18, 32, -1, sim::Boundary::zero}) ==
          "width = -1 is not allowed: an integer from 1 to 200001");
    CHECK(message_of(Cell1DParams{}) == "accepted");
    CHECK_THROWS_AS(Cell1D(Cell1DParams{-1, 32, 0, sim::Boundary::zero}), std::invalid_argument);
}
