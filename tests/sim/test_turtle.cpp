#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/lsystem.hpp"
#include "sim/check.hpp"
#include "sim/random.hpp"
#include "sim/turtle.hpp"

using sim::LSystem;
using sim::Segment2;
using sim::Segment3;
using sim::Turtle2Params;
using sim::Turtle3Params;

namespace {

// The string itself as the depth-0 axiom: the turtle reads exactly it.
std::vector<Segment2> draw(const std::string& text, Turtle2Params p = {}) {
    return sim::interpret_2d(LSystem::parse(text, {}), 0, p, false);
}
std::vector<Segment3> draw3(const std::string& text, Turtle3Params p = {}) {
    return sim::interpret_3d(LSystem::parse(text, {}), 0, p).segments;
}

bool near(glm::dvec2 a, glm::dvec2 b) {
    return glm::length(a - b) < 1e-12;
}
bool near(glm::dvec3 a, glm::dvec3 b) {
    return glm::length(a - b) < 1e-12;
}

const LSystem club_moss = LSystem::parse("F", {"F -> FF+[+F-F]-[-F+F]"});

}  // namespace

TEST_CASE("A bracketed branch returns the 2-D turtle to its pose", "[turtle]") {
    const auto plain = draw("FF");
    const auto branched = draw("F[+F-F]F");
    REQUIRE(branched.size() == 4);
    CHECK(branched.back().a == plain.back().a);  // exactly: the pop restores, nothing is recomputed
    CHECK(branched.back().b == plain.back().b);
    const auto nested = draw("F[+F[-F]F]f[-F]F");
    CHECK(near(nested.back().b, {0, 36}));
}

TEST_CASE("Plus turns right like the article's rt", "[turtle]") {
    Turtle2Params p;
    p.angle_degrees = 90;
    p.length = 1;
    const auto right = draw("+F", p), left = draw("-F", p), back = draw("|F", p);
    CHECK(near(right[0].b, {1, 0}));  // heading up, rt(90) faces +x
    CHECK(near(left[0].b, {-1, 0}));
    CHECK(near(back[0].b, {0, -1}));
    const auto straight = draw("F", Turtle2Params{});
    CHECK(near(straight[0].b, {0, 12}));  // starts at the origin heading up with d = 12
    const auto moved = draw("fF", p);
    REQUIRE(moved.size() == 1);
    CHECK(near(moved[0].a, {0, 1}));
}

TEST_CASE("Article mode draws level k segments at width 2k and fixed length", "[turtle]") {
    const auto segments = sim::interpret_2d(club_moss, 3, Turtle2Params{}, true);
    REQUIRE(segments.size() == 258);
    for (const Segment2& s : segments) {
        CHECK(s.width == 2.0 * s.level);
        CHECK(std::abs(glm::length(s.b - s.a) - 12) < 1e-9);
    }
    CHECK(segments.front().a == glm::dvec2(0, 0));
    CHECK(segments.front().level == 1);  // the first thing drawn is a tip: f(n - 1) comes before fd(d)
}

TEST_CASE("Rewrite mode widths follow the bang and brackets", "[turtle]") {
    Turtle2Params p;
    p.width = 1;
    p.width_decay = 0.5;
    const auto segments = draw("F[!F[!F]F]F", p);
    REQUIRE(segments.size() == 5);
    CHECK(segments[0].width == 1);
    CHECK(segments[1].width == 0.5);
    CHECK(segments[2].width == 0.25);
    CHECK(segments[3].width == 0.5);
    CHECK(segments[4].width == 1);
}

TEST_CASE("The turtle refuses more segments than the budget before expanding", "[turtle]") {
    CHECK_THROWS_WITH(sim::interpret_2d(club_moss, 9, Turtle2Params{}, false),
                      "depth = 9 is not allowed: a depth within the turtle's budget "
                      "(it would draw 10,077,696 segments, more than the budget of 5,000,000)");
    Turtle2Params small;
    small.segment_budget = 257;
    CHECK_THROWS_WITH(sim::interpret_2d(club_moss, 3, small, true),
                      "depth = 3 is not allowed: a depth within the turtle's budget "
                      "(it would draw 258 segments, more than the budget of 257)");
    small.segment_budget = 258;
    CHECK(sim::interpret_2d(club_moss, 3, small, true).size() == 258);
    Turtle3Params p3;
    p3.segment_budget = 1000;
    CHECK_THROWS_WITH(sim::interpret_3d(club_moss, 4, p3),
                      "depth = 4 is not allowed: a depth within the turtle's budget "
                      "(it would draw 1,296 segments, more than the budget of 1,000)");
    // so large it saturates: still refused at once
    CHECK_THROWS_AS(sim::interpret_2d(club_moss, 1000, Turtle2Params{}, false), std::invalid_argument);
}

TEST_CASE("Turtle parameters are checked", "[turtle]") {
    Turtle2Params p;
    p.length = 0;
    CHECK_THROWS_WITH(draw("F", p), Catch::Contains("length = 0 is not allowed"));
    Turtle3Params q;
    q.width_decay = -1;
    CHECK_THROWS_WITH(draw3("F", q), Catch::Contains("width_decay = -1 is not allowed"));
}

TEST_CASE("Bounds cover every end point", "[turtle]") {
    Turtle2Params p;
    p.angle_degrees = 90;
    p.length = 1;
    const auto box = sim::bounds(draw("F+F+F[-F]", p));
    CHECK(near(box.lo, {0, 0}));
    CHECK(near(box.hi, {2, 1}));
    const auto empty = sim::bounds(std::vector<Segment2>{});
    CHECK(empty.lo.x > empty.hi.x);
}

TEST_CASE("The 3-D turtle leaves the trunk straight after a pitched branch", "[turtle]") {
    const auto segments = draw3("F[&F]F");
    REQUIRE(segments.size() == 3);
    CHECK(near(segments[0].b, {0, 1, 0}));
    CHECK(near(segments[2].a, {0, 1, 0}));
    CHECK(near(segments[2].b, {0, 2, 0}));
    // the branch pitched down: away from the viewer (-U = -z), still going up
    const glm::dvec3 branch = segments[1].b - segments[1].a;
    CHECK(std::abs(branch.y - std::cos(22.5 * std::numbers::pi / 180)) < 1e-12);
    CHECK(std::abs(branch.z + std::sin(22.5 * std::numbers::pi / 180)) < 1e-12);
    // '+' turns left: towards L = -x
    const auto left = draw3("+F");
    CHECK(left[0].b.x < 0);
    CHECK(left[0].b.z == 0);
}

TEST_CASE("The 3-D turtle's rotations keep the frame orthonormal", "[turtle]") {
    sim::TurtleFrame frame;
    sim::Random rng(7);
    const std::string turns = "+-&^\\/|";
    for (int k = 0; k < 10000; ++k) {
        const char c = turns[static_cast<std::size_t>(rng.below(turns.size()))];
        frame.turn(c, 22.5 + 10 * rng.uniform());
    }
    CHECK(std::abs(glm::length(frame.heading) - 1) < 1e-12);
    CHECK(std::abs(glm::length(frame.left) - 1) < 1e-12);
    CHECK(std::abs(glm::length(frame.up) - 1) < 1e-12);
    CHECK(std::abs(glm::dot(frame.heading, frame.left)) < 1e-12);
    CHECK(std::abs(glm::dot(frame.heading, frame.up)) < 1e-12);
    CHECK(std::abs(glm::dot(frame.left, frame.up)) < 1e-12);
    CHECK(near(glm::cross(frame.heading, frame.left), frame.up));  // right-handed
}

TEST_CASE("Opposite 3-D turns undo each other", "[turtle]") {
    for (const char* pair : {"+-", "&^", "\\/", "||"}) {
        sim::TurtleFrame frame;
        frame.turn('&', 30.0);  // leave the start so every axis is involved
        const sim::TurtleFrame before = frame;
        frame.turn(pair[0], 22.5);
        frame.turn(pair[1], 22.5);
        CHECK(near(frame.heading, before.heading));
        CHECK(near(frame.left, before.left));
        CHECK(near(frame.up, before.up));
    }
}

TEST_CASE("Apple trees draw the expected segment counts", "[turtle]") {
    const LSystem apple = LSystem::parse("X", {"X -> FF-[[X]+X]+F[+FX]-X", "F -> F"});
    const LSystem abop = LSystem::parse("X", {"X -> F-[[X]+X]+F[+FX]-X", "F -> FF"});
    CHECK(sim::interpret_2d(apple, 4, Turtle2Params{}, false).size() == apple.counts(4).at('F'));
    Turtle2Params p;
    p.angle_degrees = 22.5;
    CHECK(sim::interpret_2d(abop, 5, p, false).size() == 3 * (1024 - 32) / 2);
}

TEST_CASE("the Sierpinski gasket and arrowhead draw with their own symbols: 3^(n+1) and 3^n segments", "[turtle]") {
    // ABOP Fig 1.10: F-G-G, F -> F-G+F+G-F, G -> GG at 120 degrees, drawing with F and G.
    // F's count triples and G's is 2 F's + 2 G's, so F_n = 3^n, G_n = 2 * 3^n.
    const LSystem gasket = LSystem::parse("F-G-G", {"F -> F-G+F+G-F", "G -> GG"});
    // The arrowhead: A -> B-A-B, B -> A+B+A at 60 degrees, each symbol three: 3^n.
    const LSystem arrowhead = LSystem::parse("A", {"A -> B-A-B", "B -> A+B+A"});
    // Made whole rather than assigned symbol by symbol: GCC 12 misreads short string assignments here.
    const auto turtle = [](double angle, std::string symbols) {
        Turtle2Params p;
        p.angle_degrees = angle;
        p.length = 1;
        p.draw = std::move(symbols);
        return p;
    };
    const Turtle2Params g = turtle(120, "FG"), a = turtle(60, "AB");
    for (int n = 0; n <= 6; ++n) {
        INFO("depth " << n);
        const double side = std::pow(2.0, n);
        const auto triangle = sim::interpret_2d(gasket, n, g, false);
        CHECK(sim::segment_count(gasket, n, false, g.draw) == std::uint64_t(std::pow(3, n + 1)));
        REQUIRE(triangle.size() == std::size_t(std::pow(3, n + 1)));
        const auto curve = sim::interpret_2d(arrowhead, n, a, false);
        REQUIRE(curve.size() == std::size_t(std::pow(3, n)));
        // Every step one unit long; the gasket fills an equilateral triangle of side 2^n.
        glm::dvec2 lo{1e9, 1e9}, hi{-1e9, -1e9};
        for (const auto& s : triangle) {
            CHECK(std::abs(glm::length(s.b - s.a) - 1) < 1e-9);
            lo = glm::min(lo, glm::min(s.a, s.b)), hi = glm::max(hi, glm::max(s.a, s.b));
        }
        CHECK(std::abs((hi.x - lo.x) - side * std::sqrt(3.0) / 2) < 1e-6);  // heading up: the triangle lies on its side
        CHECK(std::abs((hi.y - lo.y) - side) < 1e-6);
        // The arrowhead's ends are 2^n apart, as its triangle's base.
        CHECK(std::abs(glm::length(curve.back().b - curve.front().a) - side) < 1e-6);
    }
    // Drawing with F alone (the default), the gasket leaves out its G sides: 3^n.
    CHECK(sim::interpret_2d(gasket, 3, turtle(120, "F"), false).size() == 27);
}

TEST_CASE("draw and move take symbols, not the turtle's commands, none in both", "[turtle]") {
    const auto with = [](std::string draw_symbols, std::string move_symbols) {
        Turtle2Params p;
        p.draw = std::move(draw_symbols);
        p.move = std::move(move_symbols);
        return p;
    };
    for (const auto& [d, m] : std::vector<std::pair<std::string, std::string>>{
             {"F+", "f"}, {"FG", "Gf"}, {"FF", "f"}, {"F", "["}, {"F ", "f"}}) {
        INFO(d << " / " << m);
        CHECK_THROWS_AS(with(d, m).validate(), sim::ParameterError);
    }
    CHECK_NOTHROW(with("AB", "fg").validate());
    CHECK(draw("FfF", with("AB", "")).empty());  // F neither draws nor moves now
}

namespace {

sim::Drawing3 drawing3(const std::string& text, Turtle3Params p = {}) {
    return sim::interpret_3d(LSystem::parse(text, {}), 0, p);
}

std::vector<glm::dvec3> vertices_of(const sim::Drawing3& d, std::size_t polygon) {
    const sim::Polygon3& p = d.polygons.at(polygon);
    return {d.vertices.begin() + p.first, d.vertices.begin() + p.first + p.count};
}

}  // namespace

TEST_CASE("ABOP Fig 1.25's leaf is the hexagon its moves trace", "[turtle][polygon]") {
    // Worked by hand: the turtle starts at the origin heading +y with L = -x;
    // '-' turns right (towards +x) by 22.5 degrees, s = sin and c = cos of it.
    //   - f: (s, c)   + f: (s, 1 + c)   + f: (0, 1 + 2c)
    //   - | - f: (-s, 1 + c)   + f: (-s, c)   + f: (0, 0), the start again, left out.
    const double s = std::sin(22.5 * std::numbers::pi / 180), c = std::cos(22.5 * std::numbers::pi / 180);
    const sim::Drawing3 leaf = drawing3("{-f+f+f-|-f+f+f}");
    CHECK(leaf.segments.empty());  // f draws nothing
    REQUIRE(leaf.polygons.size() == 1);
    const std::vector<glm::dvec3> expected = {{0, 0, 0},      {s, c, 0},      {s, 1 + c, 0},
                                              {0, 1 + 2 * c, 0}, {-s, 1 + c, 0}, {-s, c, 0}};
    const auto got = vertices_of(leaf, 0);
    REQUIRE(got.size() == expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
        INFO("vertex " << k);
        CHECK(near(got[k], expected[k]));
    }
    CHECK(leaf.polygons[0].colour == 0);
}

TEST_CASE("The colour index counts apostrophes and follows the brackets", "[turtle][polygon]") {
    const sim::Drawing3 d = drawing3("F'F['F'''{+f+f}]F{'+f+f}");
    REQUIRE(d.segments.size() == 4);
    CHECK(d.segments[0].colour == 0);
    CHECK(d.segments[1].colour == 1);
    CHECK(d.segments[2].colour == 2);
    CHECK(d.segments[3].colour == 1);  // ']' restored it
    REQUIRE(d.polygons.size() == 2);
    CHECK(d.polygons[0].colour == 5);
    CHECK(d.polygons[1].colour == 2);  // the index when '}' is read
}

TEST_CASE("Polygon vertices: moves, dots, repeats, nesting and brackets", "[turtle][polygon]") {
    Turtle3Params p;
    p.angle_degrees = 90;
    // '+' turns left, towards -x, then towards -y.
    const std::vector<glm::dvec3> triangle = {{0, 0, 0}, {-1, 0, 0}, {-1, -1, 0}};
    for (const char* text : {"+{f+f}", "+{.f.+f.}", "+{f.+.f..}", "{.+f+f}", "{+f+f.}"}) {
        INFO(text);
        const sim::Drawing3 d = drawing3(text, p);
        REQUIRE(d.polygons.size() == 1);
        const auto got = vertices_of(d, 0);
        REQUIRE(got.size() == 3);
        for (std::size_t k = 0; k < 3; ++k) CHECK(near(got[k], triangle[k]));
    }
    // F inside a polygon draws and adds its vertex.
    const sim::Drawing3 drawn = drawing3("{+F+F}", p);
    CHECK(drawn.segments.size() == 2);
    REQUIRE(drawn.polygons.size() == 1);
    CHECK(drawn.polygons[0].count == 3);
    // Fewer than 3 vertices enclose nothing: dropped, not drawn.
    CHECK(drawing3("{f}", p).polygons.empty());
    CHECK(drawing3("{}", p).polygons.empty());
    CHECK(drawing3("..f.", p).polygons.empty());  // '.' outside a polygon adds to nothing
    // A bracket inside a polygon moves the turtle back, not the polygon.
    const sim::Drawing3 bracketed = drawing3("{f[+f]-f}", p);
    REQUIRE(bracketed.polygons.size() == 1);
    const auto b = vertices_of(bracketed, 0);
    REQUIRE(b.size() == 4);
    CHECK(near(b[2], {-1, 1, 0}));
    CHECK(near(b[3], {1, 1, 0}));
    // Nested: the inner polygon ends first and takes the moves made while it is open.
    const sim::Drawing3 nested = drawing3("{f+f{f+f+f}-f}", p);
    REQUIRE(nested.polygons.size() == 2);
    REQUIRE(nested.polygons[0].count == 4);  // the inner: its start and three moves
    CHECK(near(vertices_of(nested, 0)[0], {-1, 1, 0}));
    CHECK(near(vertices_of(nested, 0)[3], {-1, 0, 0}));
    REQUIRE(nested.polygons[1].count == 4);  // the outer: its start, two moves and the one after the inner
    CHECK(near(vertices_of(nested, 1)[2], {-1, 1, 0}));
    CHECK(near(vertices_of(nested, 1)[3], {-1, -1, 0}));
}

TEST_CASE("Fig 1.25's plant: vertex count, budget and bounds", "[turtle][polygon]") {
    const LSystem plant = LSystem::parse("A", {"A -> [&FL!A]/////'[&FL!A]///////'[&FL!A]", "F -> S/////F",
                                               "S -> FL", "L -> ['''^^{-f+f+f-|-f+f+f}]"});
    for (int depth = 0; depth <= 5; ++depth) {
        INFO("depth " << depth);
        const auto counts = plant.counts(depth);
        const std::uint64_t leaves = counts.count('{') ? counts.at('{') : 0;
        CHECK(sim::polygon_vertex_count(plant, depth) == 7 * leaves);  // '{' and six f
        const sim::Drawing3 d = sim::interpret_3d(plant, depth, Turtle3Params{});
        CHECK(d.polygons.size() == leaves);
        CHECK(d.vertices.size() == 6 * leaves);  // the closing vertex left out
        for (const auto& p : d.polygons) CHECK(p.colour >= 3);
        const sim::Bounds3 box = sim::bounds(d);
        for (const glm::dvec3& v : d.vertices) {
            CHECK(glm::all(glm::greaterThanEqual(v, box.lo)));
            CHECK(glm::all(glm::lessThanEqual(v, box.hi)));
        }
    }
    Turtle3Params small;
    small.vertex_budget = 100;
    const std::uint64_t vertices = sim::polygon_vertex_count(plant, 4);
    REQUIRE(vertices > 100);
    CHECK_THROWS_WITH(sim::interpret_3d(plant, 4, small),
                      Catch::StartsWith("depth = 4 is not allowed: a depth within the turtle's budget (its polygons "
                                        "would have ") &&
                          Catch::EndsWith("vertices, more than the budget of 100)"));
}
