#pragma once
// Snowflakes as a hexagonal cellular automaton (Liu & Zhang 1987, section 3;
// Packard's "Hex" rules). Every cell is ice or vapour; one ice seed sits at
// the centre. Each step, synchronously, a vapour cell with s >= 1 ice
// neighbours freezes when digit d_s of the rule code is 1. Ice never melts.
// Two extra rules from the paper: the restriction rule forbids freezing in
// the gaps between the six arms for a window of steps ("tongue" flakes), and
// the priority rule forces growth at the six arm tips ("fingered" flakes).

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sim {

// Axial coordinates (q, r), with cube coordinates (x, y, z) = (q, r, -q - r).
// The plane position is (q + r / 2, r * sqrt(3) / 2) in neighbour spacings,
// so direction u_k lies at k * 60 degrees anticlockwise from the q axis:
// u_0..u_5 = (1, 0), (0, 1), (-1, 1), (-1, 0), (0, -1), (1, -1). These are
// both the six neighbour offsets and the six arm directions.
struct HexCell {
    int q = 0;  // steps along u_0
    int r = 0;  // steps along u_1
    bool operator==(const HexCell&) const = default;
};

inline constexpr std::array<HexCell, 6> hex_directions{{{1, 0}, {0, 1}, {-1, 1}, {-1, 0}, {0, -1}, {1, -1}}};

int hex_distance(HexCell c);                   // steps from the seed: max(|x|, |y|, |z|)
long distance_squared(HexCell c);              // Euclidean, in neighbour spacings: q*q + q*r + r*r, exact
std::array<HexCell, 6> neighbours(HexCell c);  // c + u_k for k = 0..5
// The 12 symmetries of the lattice about the seed: rotate(c, k) for
// k = 0..5, each optionally followed by mirror().
HexCell rotate(HexCell c, int sixths);  // by sixths * 60 degrees anticlockwise, any integer
HexCell mirror(HexCell c);              // (q, r) -> (r, q): the reflection in the line at 30 degrees

struct SnowflakeRule {
    std::array<bool, 7> freeze{};  // freeze[s]: vapour with s ice neighbours freezes (the paper's d_s)

    // Exactly 7 characters '0'/'1', d0 first ("0101010" freezes on 1, 3 or
    // 5); d0 = 1 is refused. Throws std::invalid_argument naming the code.
    static SnowflakeRule parse(std::string_view code);
    std::string code() const;  // the 7-digit code, d0 first
};

// The restriction rule ("tongue" flakes, Fig 4). The paper does not say
// where the gaps are; this is our definition. A cell's angle from its
// nearest arm is phi = atan(sqrt(3) t / (2 - t)) with t = min(|x|, |y|, |z|)
// / max(|x|, |y|, |z|): 0 on an arm, 30 degrees half way between two arms.
// A gap is a wedge of half-width half_angle centred half way between arms.
struct Restriction {
    int first = 1;             // first step of the window, >= 1
    int last = 0;              // last step of the window, inclusive; none when last < first
    int min_radius = 2;        // hex distance where the gaps start, >= 1 (the seed's ring must be free to grow)
    double half_angle = 15.0;  // degrees, above 0 and at most 30 (30 closes everything off the arms)

    bool active(int step) const;      // first <= step <= last
    bool in_region(HexCell c) const;  // hex distance >= min_radius and 30 - phi <= half_angle
};

// The priority rule ("fingered" flakes, Fig 5), our definition. The tip of
// the arm along u_k is m_k, the largest m such that every cell m' * u_k for
// m' = 0..m is ice (the unbroken run from the seed). At a priority step the
// cell (m_k + 1) * u_k freezes whatever the rule and the restriction say,
// and so do the vapour cells on its ring (hex distance m_k + 1) that touch
// ice and lie within `width` lattice rows of the arm line on the tip's side
// (a row is sqrt(3) / 2 neighbour spacings). Any rule with d1 = 1 grows the
// tips every step anyway (the cell beyond a tip has one ice neighbour), so
// for those only width > 0 or exclusive changes anything. Exclusive reads
// the paper's "then grow by the rule again" literally: during a priority
// step only the forced cells freeze.
struct Priority {
    std::vector<int> steps;  // steps that force the tips (step 1 is the first update), each >= 1
    int width = 0;           // rows either side of the arm line forced too, 0..1000000
    bool exclusive = false;  // true: the rule rests during priority steps, only forced cells freeze

    bool active(int step) const;  // step is listed
};

struct SnowflakeParams {
    SnowflakeRule rule;       // which ice-neighbour counts freeze
    Restriction restriction;  // gaps closed during a window (none by default)
    Priority priority;        // tips forced at some steps (none by default)

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

class Snowflake {
public:
    explicit Snowflake(const SnowflakeParams& params);  // one ice seed at (0, 0)

    // Synchronous, from the state before the step: a vapour cell with s >= 1
    // ice neighbours freezes if rule.freeze[s], unless the restriction is
    // active and the cell is in its region (or an exclusive priority step
    // rests the rule); at a priority step the tip cells (and width cells)
    // freeze too, restriction or not.
    void step();

    int steps() const { return steps_; }                               // updates done so far
    long ice_count() const { return static_cast<long>(ice_.size()); }  // the seed included
    int radius() const { return radius_; }                             // largest hex distance of the ice
    double euclidean_radius() const;                                   // largest sqrt(distance_squared) of the ice
    bool is_ice(HexCell c) const { return frozen_at(c) >= 0; }         // any cell, stored or not
    int frozen_at(HexCell c) const;                                    // step c froze at, 0 for the seed, -1 if vapour
    int arm_length(int direction) const;                               // m_k for k = direction mod 6
    std::vector<HexCell> ice_cells() const;                            // by step frozen, then r, then q
    std::size_t storage_cells() const { return sites_.size(); }        // <= max(17, 4 radius + 5)^2: grows with the ice
    const SnowflakeParams& params() const { return params_; }
    // Bytes of the store at its peak when the ice reaches hex distance
    // `radius`: the store then and the one it grew from, both alive while
    // it copies. For memory estimates, before anything runs.
    static double storage_peak_bytes(int radius);

private:
    struct Site {
        std::int32_t frozen_at = -1;      // step frozen, -1 while vapour
        std::uint8_t ice_neighbours = 0;  // kept up to date as neighbours freeze
        std::uint8_t marks = 0;           // queued / held / freezing bits used inside step()
    };
    std::size_t side() const { return 2 * static_cast<std::size_t>(half_) + 1; }
    std::size_t index(HexCell c) const;                       // c must lie inside the store
    HexCell cell_at(std::size_t i) const;                     // the inverse of index()
    std::array<std::ptrdiff_t, 6> neighbour_offsets() const;  // index(c + u_k) - index(c)
    bool stored(HexCell c) const;                             // |q|, |r| <= half_
    void grow_storage();                                      // doubles the store until the margin holds again
    void force_tips();                                        // adds the priority cells to freezing_
    void freeze_now(std::size_t i, int step);                 // marks site i ice and counts it in its neighbours

    SnowflakeParams params_;
    int half_ = 0;                               // the store covers |q|, |r| <= half_
    std::vector<Site> sites_;                    // (2 half_ + 1)^2 sites, row r, column q
    std::vector<HexCell> ice_;                   // ice cells by step frozen, then r, then q
    std::size_t fresh_ = 0;                      // ice_[fresh_..] froze last step: their neighbours' counts changed
    std::vector<HexCell> held_;                  // cells the rule would freeze but the restriction holds back
    std::vector<std::size_t> queue_, freezing_;  // scratch for step(): store indices
    long max_distance_squared_ = 0;              // of the ice cells
    int radius_ = 0;                             // largest hex distance of the ice cells
    int steps_ = 0;                              // updates done
};

// The paper's mass M(l) for l = 1..max_l (element l - 1): ice cells with
// distance_squared <= l * l. Throws std::invalid_argument when max_l < 0.
std::vector<long> mass_within(const Snowflake& flake, int max_l);

}  // namespace sim
