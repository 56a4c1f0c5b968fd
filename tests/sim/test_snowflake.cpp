#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/snowflake.hpp"

using sim::HexCell;
using sim::Priority;
using sim::Restriction;
using sim::Snowflake;
using sim::SnowflakeParams;
using sim::SnowflakeRule;

namespace {

SnowflakeParams params_of(const std::string& code) {
    SnowflakeParams p;
    p.rule = SnowflakeRule::parse(code);
    return p;
}

// Rule number n in 0..63 as a code with d0 = 0: bit s - 1 of n is d_s.
std::string code_of(int n) {
    std::string code = "0";
    for (int s = 1; s <= 6; ++s) code += (n >> (s - 1)) & 1 ? '1' : '0';
    return code;
}

HexCell symmetry(HexCell c, int g) {  // g = 0..11: rotation g % 6, mirrored first when g >= 6
    return sim::rotate(g >= 6 ? sim::mirror(c) : c, g % 6);
}

// Every cell near the crystal has the step it froze at in common with its 11 images.
bool symmetric(const Snowflake& flake) {
    const int n = flake.radius() + 2;
    for (int q = -n; q <= n; ++q)
        for (int r = -n; r <= n; ++r)
            for (int g = 1; g < 12; ++g)
                if (flake.frozen_at({q, r}) != flake.frozen_at(symmetry({q, r}, g))) return false;
    return true;
}

// Section 3 applied to every cell of a box, written from the definitions
// alone: no frontier, no incremental counts.
class WholePlane {
public:
    WholePlane(const SnowflakeParams& p, int steps) : p_(p), n_(steps + 3), frozen_(side() * side(), -1) {
        at({0, 0}) = 0;
    }

    int frozen_at(HexCell c) const { return inside(c) ? frozen_[index(c)] : -1; }
    int n() const { return n_; }

    void step() {
        const int t = ++steps_;
        std::vector<int> next = frozen_;
        for (int q = -n_; q <= n_; ++q)
            for (int r = -n_; r <= n_; ++r) {
                const HexCell c{q, r};
                if (frozen_at(c) >= 0) continue;
                const int s = ice_neighbours(c);
                if (s == 0 || !p_.rule.freeze[s]) continue;
                if (p_.restriction.active(t) && p_.restriction.in_region(c)) continue;
                next[index(c)] = t;
            }
        if (p_.priority.active(t) && p_.priority.exclusive) next = frozen_;  // the rule rests
        if (p_.priority.active(t))
            for (int k = 0; k < 6; ++k) {
                const HexCell u = sim::hex_directions[k];
                int m = 0;
                while (frozen_at({(m + 1) * u.q, (m + 1) * u.r}) >= 0) ++m;
                // Cells on ring m + 1 facing this tip (2q' + r' > 0 once the arm is turned onto u_0)
                // within width rows of the arm line (|r'| <= width); the tip itself has r' = 0.
                for (int q = -n_; q <= n_; ++q)
                    for (int r = -n_; r <= n_; ++r) {
                        const HexCell c{q, r};
                        const HexCell turned = sim::rotate(c, -k);
                        if (sim::hex_distance(c) != m + 1 || 2 * turned.q + turned.r <= 0) continue;
                        if (std::abs(turned.r) > p_.priority.width) continue;
                        if (frozen_at(c) >= 0 || (turned.r != 0 && ice_neighbours(c) == 0)) continue;
                        next[index(c)] = t;
                    }
            }
        frozen_ = next;
    }

private:
    std::size_t side() const { return 2 * static_cast<std::size_t>(n_) + 1; }
    bool inside(HexCell c) const { return std::abs(c.q) <= n_ && std::abs(c.r) <= n_; }
    std::size_t index(HexCell c) const {
        return static_cast<std::size_t>(c.r + n_) * side() + static_cast<std::size_t>(c.q + n_);
    }
    int& at(HexCell c) { return frozen_[index(c)]; }
    int ice_neighbours(HexCell c) const {
        int s = 0;
        for (HexCell nb : sim::neighbours(c)) s += frozen_at(nb) >= 0;
        return s;
    }

    SnowflakeParams p_;
    int n_;
    std::vector<int> frozen_;
    int steps_ = 0;
};

// Settings of the restriction and priority rules the tests run through.
std::vector<SnowflakeParams> extra_settings() {
    std::vector<SnowflakeParams> out;
    for (const char* code : {"0101010", "0100010", "0100000", "0110100", "0110000", "0010000", "0100100"}) {
        SnowflakeParams p = params_of(code);
        p.restriction = Restriction{1, 16, 2, 15.0};
        out.push_back(p);
        p.restriction = Restriction{5, 22, 3, 30.0};
        out.push_back(p);
        p.restriction = Restriction{2, 9, 1, 7.5};
        p.priority = Priority{{4, 5}, 0};
        out.push_back(p);
        p.restriction = Restriction{};
        p.priority = Priority{{4}, 0};
        out.push_back(p);
        p.priority = Priority{{7, 8}, 2};
        out.push_back(p);
        p.priority = Priority{{1, 3, 6, 10, 11}, 5};
        p.restriction = Restriction{3, 12, 2, 20.0};
        out.push_back(p);
        p.priority = Priority{{4, 5, 9, 21}, 1, true};
        out.push_back(p);
        p.priority = Priority{{7, 8, 16, 17}, 0, true};
        p.restriction = Restriction{};
        out.push_back(p);
    }
    return out;
}

std::string message_of(const SnowflakeParams& p) {
    try {
        p.validate();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "accepted";
}

std::string parse_message(const std::string& code) {
    try {
        SnowflakeRule::parse(code);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "accepted";
}

}  // namespace

TEST_CASE("hex lattice helpers agree with cube coordinates", "[snowflake]") {
    for (int k = 0; k < 6; ++k) {
        const HexCell u = sim::hex_directions[k];
        CHECK(sim::hex_distance(u) == 1);
        CHECK(sim::distance_squared(u) == 1);
        CHECK(sim::rotate({1, 0}, k) == u);  // u_k lies at k * 60 degrees
        CHECK(sim::rotate(u, 1) == sim::hex_directions[(k + 1) % 6]);
        CHECK(sim::neighbours({3, -2})[static_cast<std::size_t>(k)] == HexCell{3 + u.q, -2 + u.r});
    }
    CHECK(sim::distance_squared({1, 1}) == 3);  // half way between two arms: sqrt(3) away
    CHECK(sim::hex_distance({1, 1}) == 2);
    CHECK(sim::hex_distance({2, -5}) == 5);
    CHECK(sim::mirror(sim::hex_directions[0]) == sim::hex_directions[1]);
    CHECK(sim::rotate({2, 3}, -1) == sim::rotate({2, 3}, 5));
    CHECK(sim::rotate({2, 3}, 13) == sim::rotate({2, 3}, 1));
    for (int q = -7; q <= 7; ++q)
        for (int r = -7; r <= 7; ++r) {
            const HexCell c{q, r};
            CHECK(sim::rotate(c, 6) == c);
            CHECK(sim::mirror(sim::mirror(c)) == c);
            for (int g = 0; g < 12; ++g) {
                REQUIRE(sim::hex_distance(symmetry(c, g)) == sim::hex_distance(c));
                REQUIRE(sim::distance_squared(symmetry(c, g)) == sim::distance_squared(c));
            }
            // distance_squared is |q u_0 + r u_1|^2 in the plane.
            const double x = q + 0.5 * r, y = r * std::sqrt(3.0) / 2;
            CHECK(std::abs(x * x + y * y - static_cast<double>(sim::distance_squared(c))) < 1e-9);
        }
}

TEST_CASE("rule 0100000 grows Packard's Hex1 snowflake", "[snowflake]") {
    const std::vector<long> expected{1, 7, 13, 31, 37, 55, 85, 127, 133, 151, 181, 235};
    Snowflake flake(params_of("0100000"));
    for (std::size_t t = 0; t < expected.size(); ++t) {
        INFO("step " << t);
        CHECK(flake.steps() == static_cast<int>(t));
        CHECK(flake.ice_count() == expected[t]);
        flake.step();
    }
}

TEST_CASE("every rule with d0 0 grows a crystal with all 12 symmetries at every step", "[snowflake]") {
    for (int n = 0; n < 64; ++n) {
        INFO("rule " << code_of(n));
        Snowflake flake(params_of(code_of(n)));
        for (int t = 0; t < 30; ++t) {
            flake.step();
            REQUIRE(symmetric(flake));
        }
    }
}

TEST_CASE("restriction and priority keep the crystal exactly symmetric", "[snowflake]") {
    for (const SnowflakeParams& p : extra_settings()) {
        INFO("rule " << p.rule.code() << " restriction " << p.restriction.first << ".." << p.restriction.last
                     << " priority width " << p.priority.width << " exclusive " << p.priority.exclusive);
        Snowflake flake(p);
        for (int t = 0; t < 30; ++t) {
            flake.step();
            REQUIRE(symmetric(flake));
        }
    }
}

TEST_CASE("the frontier update equals a whole-plane synchronous update", "[snowflake]") {
    std::vector<SnowflakeParams> all = extra_settings();
    for (int n = 0; n < 64; ++n) all.push_back(params_of(code_of(n)));
    const int steps = 24;
    for (const SnowflakeParams& p : all) {
        INFO("rule " << p.rule.code() << " restriction " << p.restriction.first << ".." << p.restriction.last
                     << " priority width " << p.priority.width << " exclusive " << p.priority.exclusive);
        Snowflake flake(p);
        WholePlane reference(p, steps);
        for (int t = 1; t <= steps; ++t) {
            flake.step();
            reference.step();
            long ice = 0;
            for (int q = -reference.n(); q <= reference.n(); ++q)
                for (int r = -reference.n(); r <= reference.n(); ++r) {
                    REQUIRE(flake.frozen_at({q, r}) == reference.frozen_at({q, r}));
                    ice += reference.frozen_at({q, r}) >= 0;
                }
            REQUIRE(flake.ice_count() == ice);
        }
    }
}

TEST_CASE("exactly the 16 rules with d1 and d2 set grow the full hexagon", "[snowflake]") {
    // A full hexagon's outer ring has 1 ice neighbour at the 6 corners and 2
    // along the edges, and nothing else touches ice: d3..d6 never matter.
    for (int n = 0; n < 64; ++n) {
        const std::string code = code_of(n);
        INFO("rule " << code);
        const bool full_rule = code[1] == '1' && code[2] == '1';
        Snowflake flake(params_of(code));
        bool full = true;
        for (long t = 1; t <= 40; ++t) {
            flake.step();
            full = full && flake.ice_count() == 3 * t * (t + 1) + 1 && flake.radius() == t;
        }
        CHECK(full == full_rule);
    }
}

TEST_CASE("ice never melts and the full hexagon freezes ring by ring", "[snowflake]") {
    for (const char* code : {"0110000", "0101010", "0100000", "0110100"}) {
        INFO("rule " << code);
        Snowflake flake(params_of(code));
        std::vector<HexCell> before = flake.ice_cells();
        for (int t = 1; t <= 40; ++t) {
            flake.step();
            for (HexCell c : before) REQUIRE(flake.frozen_at(c) >= 0);
            for (HexCell c : before) REQUIRE(flake.frozen_at(c) < t);  // its old step, unchanged
            const std::vector<HexCell> now = flake.ice_cells();
            REQUIRE(std::equal(before.begin(), before.end(), now.begin()));  // old cells first, same order
            for (std::size_t i = before.size(); i < now.size(); ++i) REQUIRE(flake.frozen_at(now[i]) == t);
            before = now;
        }
    }
    Snowflake full(params_of("0110000"));
    for (int t = 0; t < 50; ++t) full.step();
    for (int q = -52; q <= 52; ++q)
        for (int r = -52; r <= 52; ++r) {
            const int d = sim::hex_distance({q, r});
            REQUIRE(full.frozen_at({q, r}) == (d <= 50 ? d : -1));
        }
    CHECK(full.radius() == 50);
    CHECK(full.euclidean_radius() == 50.0);  // the corners, on the arms
    CHECK(full.arm_length(0) == 50);
    CHECK(full.arm_length(-1) == 50);
}

TEST_CASE("ice cells are listed by step frozen then r then q", "[snowflake]") {
    Snowflake flake(params_of("0101010"));
    for (int t = 0; t < 20; ++t) flake.step();
    const std::vector<HexCell> cells = flake.ice_cells();
    CHECK(static_cast<long>(cells.size()) == flake.ice_count());
    CHECK(cells.front() == HexCell{0, 0});
    for (std::size_t i = 1; i < cells.size(); ++i) {
        const HexCell a = cells[i - 1], b = cells[i];
        const int fa = flake.frozen_at(a), fb = flake.frozen_at(b);
        REQUIRE((fa < fb || (fa == fb && (a.r < b.r || (a.r == b.r && a.q < b.q)))));
    }
}

TEST_CASE("restriction forbids freezing in its region only during its window", "[snowflake]") {
    struct Case {
        const char* code;
        Restriction restriction;
    };
    // The paper's Fig 4: (a) 0100000 closed during steps 1..16, (b) 0110100 during 5..22.
    for (const Case& k : {Case{"0100000", {1, 16, 2, 15.0}}, Case{"0110100", {5, 22, 2, 15.0}},
                          Case{"0110000", {3, 10, 4, 25.0}}, Case{"0101010", {1, 30, 2, 10.0}}}) {
        INFO("rule " << k.code);
        SnowflakeParams p = params_of(k.code);
        p.restriction = k.restriction;
        Snowflake flake(p);
        for (int t = 0; t < 60; ++t) flake.step();
        long inside_window = 0, after_window = 0, outside_region_in_window = 0;
        for (HexCell c : flake.ice_cells()) {
            const int f = flake.frozen_at(c);
            const bool in = k.restriction.in_region(c);
            inside_window += in && k.restriction.active(f);
            after_window += in && f > k.restriction.last;
            outside_region_in_window += !in && k.restriction.active(f);
        }
        CHECK(inside_window == 0);
        CHECK(after_window > 0);  // the gaps fill once the window closes
        CHECK(outside_region_in_window > 0);
        Snowflake free(params_of(k.code));
        for (int t = 0; t < 60; ++t) free.step();
        long differing = 0;  // not just the counts: 0100000 has 6769 ice cells at step 60 either way
        for (int q = -61; q <= 61; ++q)
            for (int r = -61; r <= 61; ++r) differing += free.is_ice({q, r}) != flake.is_ice({q, r});
        CHECK(differing > 0);
    }
}

TEST_CASE("the restriction region is symmetric and matches the angle from the nearest arm", "[snowflake]") {
    long boundary = 0, checked = 0;
    for (double half_angle : {0.5, 5.0, 7.5, 10.0, 15.0, 20.0, 25.0, 29.0, 30.0}) {
        for (int min_radius : {1, 2, 6}) {
            const Restriction region{1, 10, min_radius, half_angle};
            for (int q = -30; q <= 30; ++q)
                for (int r = -30; r <= 30; ++r) {
                    const HexCell c{q, r};
                    if (sim::hex_distance(c) > 30) continue;
                    const bool in = region.in_region(c);
                    for (int g = 1; g < 12; ++g) REQUIRE(region.in_region(symmetry(c, g)) == in);
                    if (sim::hex_distance(c) >= min_radius)  // one ray, one answer
                        for (int m = 2; m <= 4; ++m) REQUIRE(region.in_region({m * q, m * r}) == in);
                    if (c == HexCell{0, 0}) {
                        CHECK_FALSE(in);
                        continue;
                    }
                    // The angle in the plane, folded onto the nearest arm.
                    const double x = q + 0.5 * r, y = r * std::sqrt(3.0) / 2;
                    const double degrees = std::atan2(y, x) * 180.0 / std::numbers::pi;
                    const double within = std::fmod(degrees + 360.0, 60.0);
                    const double phi = std::min(within, 60.0 - within);
                    const double margin = 30.0 - phi - half_angle;
                    if (std::abs(margin) < 1e-9) {
                        ++boundary;
                        continue;
                    }
                    ++checked;
                    REQUIRE(in == (sim::hex_distance(c) >= min_radius && margin < 0));
                }
        }
    }
    CHECK(checked > 10000);
    CHECK(boundary > 0);  // half_angle 30 puts the arms on the boundary (phi = 0)
}

TEST_CASE("priority alone grows six straight arms", "[snowflake]") {
    SnowflakeParams p = params_of("0000000");
    p.priority.steps = {1, 2, 3, 4, 5};
    Snowflake flake(p);
    for (int t = 0; t < 8; ++t) flake.step();  // steps 6..8 freeze nothing
    CHECK(flake.ice_count() == 31);
    for (int k = 0; k < 6; ++k) {
        CHECK(flake.arm_length(k) == 5);
        for (int m = 1; m <= 5; ++m) {
            const HexCell u = sim::hex_directions[k];
            CHECK(flake.frozen_at({m * u.q, m * u.r}) == m);
        }
    }
    CHECK(flake.radius() == 5);
}

TEST_CASE("priority forces the cells beyond the tips whatever the rule says", "[snowflake]") {
    // 0010000 never freezes the cell beyond a tip (it has 1 ice neighbour).
    SnowflakeParams p = params_of("0010000");
    p.priority.steps = {1, 4};
    Snowflake flake(p);
    flake.step();
    CHECK(flake.ice_count() == 7);  // the six tips at step 1
    for (int t = 2; t <= 3; ++t) flake.step();
    const long before = flake.ice_count();
    const int tip = flake.arm_length(0);
    flake.step();
    for (int k = 0; k < 6; ++k) {
        const HexCell u = sim::hex_directions[k];
        CHECK(flake.frozen_at({(tip + 1) * u.q, (tip + 1) * u.r}) == 4);
        CHECK(flake.arm_length(k) == tip + 1);
    }
    CHECK(flake.ice_count() >= before + 6);

    // Width 1: the tip cell and its two ring neighbours that touch ice.
    SnowflakeParams wide = params_of("0000000");
    wide.priority = Priority{{1, 2}, 1};
    Snowflake fan(wide);
    fan.step();
    CHECK(fan.ice_count() == 7);  // ring 1 is all tips and tip neighbours
    fan.step();
    // Ring 2: the 6 corners and, beside each, the edge cells within 1 row (12 cells), all touching ring 1.
    CHECK(fan.ice_count() == 7 + 12);
    CHECK(fan.frozen_at({1, 1}) == 2);
    CHECK(fan.frozen_at({2, -1}) == 2);
}

TEST_CASE("priority at the tips alone changes nothing for rules with d1 set", "[snowflake]") {
    // The cell beyond a tip has exactly one ice neighbour: d1 = 1 freezes it anyway.
    for (int n = 1; n < 64; n += 2) {
        SnowflakeParams p = params_of(code_of(n));
        INFO("rule " << p.rule.code());
        Snowflake plain(p);
        p.priority.steps = {2, 4, 5, 9};
        Snowflake forced(p);
        for (int t = 0; t < 15; ++t) {
            plain.step();
            forced.step();
        }
        CHECK(forced.ice_cells() == plain.ice_cells());
        CHECK(plain.radius() == 15);  // and the arms grow one cell a step
    }
}

TEST_CASE("an exclusive priority step freezes only the forced cells", "[snowflake]") {
    // The paper's Fig 5(c): 0110000 with priority at steps 7 and 8.
    SnowflakeParams p = params_of("0110000");
    p.priority = Priority{{7, 8}, 0, true};
    Snowflake flake(p);
    for (int t = 0; t < 6; ++t) flake.step();
    CHECK(flake.ice_count() == 127);  // the full hexagon of radius 6
    flake.step();
    CHECK(flake.ice_count() == 133);  // plus the six tips
    flake.step();
    CHECK(flake.ice_count() == 139);
    CHECK(flake.arm_length(0) == 8);
    flake.step();  // the rule is back, and the cells that waited since step 7 are asked again
    CHECK(flake.frozen_at({5, 2}) == 9);    // ring 7, two ice neighbours
    CHECK(flake.frozen_at({9, 0}) == 9);    // beyond the tip, one
    CHECK(flake.frozen_at({7, -1}) == -1);  // beside the finger: three, and d3 = 0
    CHECK(flake.frozen_at({1, 6}) == -1);
    CHECK(symmetric(flake));
}

TEST_CASE("snowflake rule codes parse and bad ones are rejected with messages naming them", "[snowflake]") {
    CHECK(SnowflakeRule::parse("0101010").code() == "0101010");
    const SnowflakeRule odd = SnowflakeRule::parse("0101010");
    CHECK(odd.freeze == std::array<bool, 7>{false, true, false, true, false, true, false});
    for (int n = 0; n < 64; ++n) CHECK(SnowflakeRule::parse(code_of(n)).code() == code_of(n));
    CHECK(parse_message("0102010") == "rule = \"0102010\" is not allowed: a rule code is 7 binary digits d0..d6");
    CHECK(parse_message("01010") == "rule = \"01010\" is not allowed: a rule code is 7 binary digits d0..d6");
    CHECK(parse_message("abcdefg") == "rule = \"abcdefg\" is not allowed: a rule code is 7 binary digits d0..d6");
    CHECK(parse_message("01010100") == "rule = \"01010100\" is not allowed: a rule code is 7 binary digits d0..d6");
    CHECK(parse_message("1100000") ==
          "rule = \"1100000\" is not allowed: d0 = 1 freezes vapour with no ice neighbour, filling the plane");
}

TEST_CASE("snowflake parameters are validated with messages naming them", "[snowflake]") {
    CHECK(message_of(SnowflakeParams{}) == "accepted");
    SnowflakeParams p;
    p.rule.freeze[0] = true;
    CHECK(message_of(p) ==
          "rule = \"1000000\" is not allowed: d0 = 1 freezes vapour with no ice neighbour, filling the plane");
    CHECK_THROWS_AS(Snowflake(p), std::invalid_argument);
    p = SnowflakeParams{};
    p.restriction.first = 0;
    CHECK(message_of(p) ==
          "restriction.first = 0 is not allowed: an integer from 1 to 1000000000");
    p = SnowflakeParams{};
    p.restriction.min_radius = 0;
    CHECK(message_of(p) ==
          "restriction.min_radius = 0 is not allowed: an integer from 1 to 1000000000");
    p = SnowflakeParams{};
    p.restriction.half_angle = 0.0;
    CHECK(message_of(p) ==
          "restriction.half_angle = 0 is not allowed: a number of degrees above 0 (an empty wedge) and at most 30 "
          "(past it the wedges overlap the arms)");
    p.restriction.half_angle = 31.0;
    CHECK(message_of(p) ==
          "restriction.half_angle = 31 is not allowed: a number of degrees above 0 (an empty wedge) and at most 30 "
          "(past it the wedges overlap the arms)");
    p.restriction.half_angle = 30.0;
    CHECK(message_of(p) == "accepted");
    p.priority.steps = {3, 0};
    CHECK(message_of(p) == "priority.steps = 0 is not allowed: an integer from 1 to 1000000000");
    p.priority.steps = {3};
    p.priority.width = -1;
    CHECK(message_of(p) == "priority.width = -1 is not allowed: an integer from 0 to 1000000");
    p.priority.width = 0;
    p.restriction.first = 5;
    p.restriction.last = 4;  // an empty window is allowed
    CHECK(message_of(p) == "accepted");
    CHECK_FALSE(p.restriction.active(4));
    CHECK_FALSE(p.restriction.active(5));
    CHECK(p.priority.active(3));
    CHECK_FALSE(p.priority.active(4));
}

TEST_CASE("snowflake storage grows with the crystal", "[snowflake]") {
    Snowflake flake(params_of("0110000"));
    for (int t = 0; t < 10; ++t) flake.step();
    const std::size_t small = flake.storage_cells();
    for (int t = 10; t < 200; ++t) {
        flake.step();
        const std::size_t box = static_cast<std::size_t>(2 * flake.radius() + 1);
        const std::size_t bound = static_cast<std::size_t>(std::max(17, 4 * flake.radius() + 5));
        REQUIRE(flake.storage_cells() <= bound * bound);
        if (flake.radius() >= 8) REQUIRE(flake.storage_cells() <= 6 * box * box);
    }
    CHECK(small < 2000);
    CHECK(flake.storage_cells() > 100 * small);
    CHECK(flake.frozen_at({1000000, -5}) == -1);  // far outside the store: vapour
}

TEST_CASE("mass within l matches a brute-force count", "[snowflake]") {
    for (const char* code : {"0110000", "0101010"}) {
        Snowflake flake(params_of(code));
        for (int t = 0; t < 25; ++t) flake.step();
        const std::vector<long> mass = sim::mass_within(flake, 40);
        REQUIRE(mass.size() == 40);
        for (int l = 1; l <= 40; ++l) {
            long count = 0;
            for (int q = -30; q <= 30; ++q)
                for (int r = -30; r <= 30; ++r)
                    count += flake.is_ice({q, r}) && sim::distance_squared({q, r}) <= long{l} * l;
            REQUIRE(mass[static_cast<std::size_t>(l - 1)] == count);
        }
        CHECK(mass.back() == flake.ice_count());  // everything lies within 25 < 40
    }
    CHECK(sim::mass_within(Snowflake(SnowflakeParams{}), 0).empty());
    CHECK_THROWS_AS(sim::mass_within(Snowflake(SnowflakeParams{}), -1), std::invalid_argument);
}
