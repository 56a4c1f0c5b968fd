#include "sim/snowflake.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <numbers>

#include "sim/check.hpp"

namespace sim {

namespace {

// Bits of Site::marks, so that no cell enters a list twice in one step.
constexpr std::uint8_t queued = 1, held = 2, freezing = 4;

constexpr int first_half = 8;  // the first store covers |q|, |r| <= 8
constexpr int margin = 2;      // a step reaches the new ice's neighbours: hex distance radius + 2

HexCell operator+(HexCell a, HexCell b) { return {a.q + b.q, a.r + b.r}; }
HexCell operator*(int m, HexCell u) { return {m * u.q, m * u.r}; }

// A rule code as messages show it: "\"0101010\"".
std::string quoted(std::string_view code) {
    std::string text = "\"";  // appended, not operator+: GCC 12 warns falsely (-Wrestrict) on "\"" + string
    text.append(code).push_back('"');
    return text;
}

const char* const fills_the_plane = "d0 = 1 freezes vapour with no ice neighbour, filling the plane";

}  // namespace

int hex_distance(HexCell c) { return (std::abs(c.q) + std::abs(c.r) + std::abs(c.q + c.r)) / 2; }

long distance_squared(HexCell c) {
    const long q = c.q, r = c.r;
    return q * q + q * r + r * r;
}

std::array<HexCell, 6> neighbours(HexCell c) {
    std::array<HexCell, 6> out;
    for (int k = 0; k < 6; ++k) out[k] = c + hex_directions[k];
    return out;
}

HexCell rotate(HexCell c, int sixths) {
    for (int k = ((sixths % 6) + 6) % 6; k > 0; --k) c = {-c.r, c.q + c.r};  // u_0 -> u_1 -> u_2 ...
    return c;
}

HexCell mirror(HexCell c) { return {c.r, c.q}; }

SnowflakeRule SnowflakeRule::parse(std::string_view code) {
    const bool binary = code.size() == 7 && code.find_first_not_of("01") == std::string_view::npos;
    if (!binary) throw ParameterError("rule", quoted(code), "a rule code is 7 binary digits d0..d6");
    SnowflakeRule rule;
    for (int s = 0; s < 7; ++s) rule.freeze[s] = code[s] == '1';
    if (rule.freeze[0]) throw ParameterError("rule", quoted(code), fills_the_plane);
    return rule;
}

std::string SnowflakeRule::code() const {
    std::string out;
    for (bool f : freeze) out += f ? '1' : '0';
    return out;
}

bool Restriction::active(int step) const { return first <= step && step <= last; }

bool Restriction::in_region(HexCell c) const {
    const int x = std::abs(c.q), y = std::abs(c.r), z = std::abs(c.q + c.r);
    const int low = std::min({x, y, z}), high = std::max({x, y, z});  // high is the hex distance
    if (high < min_radius) return false;
    // phi depends on (a, b) alone, which the 12 symmetries keep (they permute
    // and negate cube coordinates): all images of a cell get the same answer.
    // Reduced by their gcd so that every cell on one ray gets the same too.
    const int g = std::gcd(low, high), a = low / g, b = high / g;
    const double phi = std::atan2(std::sqrt(3.0) * a, 2.0 * b - a) * (180.0 / std::numbers::pi);
    return 30.0 - phi <= half_angle;
}

bool Priority::active(int step) const { return std::find(steps.begin(), steps.end(), step) != steps.end(); }

void SnowflakeParams::validate() const {
    if (rule.freeze[0]) throw ParameterError("rule", quoted(rule.code()), fills_the_plane);
    require_integer("restriction.first", restriction.first, 1, 1000000000);
    require_integer("restriction.last", restriction.last, 0, 1000000000);
    require_integer("restriction.min_radius", restriction.min_radius, 1, 1000000000);
    const double h = restriction.half_angle;
    if (!(std::isfinite(h) && h > 0.0 && h <= 30.0))
        throw ParameterError("restriction.half_angle", shown(h),
                             "a number of degrees above 0 (an empty wedge) and at most 30 (past it the wedges "
                             "overlap the arms)");
    for (int s : priority.steps) require_integer("priority.steps", s, 1, 1000000000);
    require_integer("priority.width", priority.width, 0, 1000000);
}

Snowflake::Snowflake(const SnowflakeParams& params) : params_(params), half_(first_half) {
    params_.validate();
    sites_.assign(side() * side(), Site{});
    freeze_now(index({0, 0}), 0);
}

std::size_t Snowflake::index(HexCell c) const {
    return static_cast<std::size_t>(c.r + half_) * side() + static_cast<std::size_t>(c.q + half_);
}

HexCell Snowflake::cell_at(std::size_t i) const {
    return {static_cast<int>(i % side()) - half_, static_cast<int>(i / side()) - half_};
}

std::array<std::ptrdiff_t, 6> Snowflake::neighbour_offsets() const {
    const auto row = static_cast<std::ptrdiff_t>(side());  // u_1 = (0, 1) is one row up
    return {1, row, row - 1, -1, -row, 1 - row};           // u_0..u_5 as in hex_directions
}

bool Snowflake::stored(HexCell c) const { return std::abs(c.q) <= half_ && std::abs(c.r) <= half_; }

int Snowflake::frozen_at(HexCell c) const { return stored(c) ? sites_[index(c)].frozen_at : -1; }

double Snowflake::euclidean_radius() const { return std::sqrt(static_cast<double>(max_distance_squared_)); }

int Snowflake::arm_length(int direction) const {
    const HexCell u = hex_directions[((direction % 6) + 6) % 6];
    int m = 0;
    while (is_ice((m + 1) * u)) ++m;
    return m;
}

std::vector<HexCell> Snowflake::ice_cells() const { return ice_; }

// Only cells whose ice-neighbour count changed last step (the neighbours of
// the fresh ice) can change their answer now: any other vapour cell was
// already asked with the same count and said no, or is in held_. So a step
// costs the new ice, not the whole frontier.
void Snowflake::step() {
    const int t = steps_ + 1;
    const Restriction& restriction = params_.restriction;
    const bool restricted = restriction.active(t);
    const std::array<std::ptrdiff_t, 6> offsets = neighbour_offsets();
    auto enqueue = [&](std::size_t i) {
        Site& s = sites_[i];
        if (s.frozen_at >= 0 || (s.marks & queued)) return;
        s.marks |= queued;
        queue_.push_back(i);
    };
    for (std::size_t k = fresh_; k < ice_.size(); ++k) {
        const std::size_t i = index(ice_[k]);
        for (std::ptrdiff_t offset : offsets) enqueue(i + static_cast<std::size_t>(offset));  // wraps to i - |offset|
    }
    if (!restricted && !held_.empty()) {  // the window is over: ask the held cells again
        for (HexCell c : held_) {
            sites_[index(c)].marks &= static_cast<std::uint8_t>(~held);
            enqueue(index(c));
        }
        held_.clear();
    }

    freezing_.clear();
    const bool forced = params_.priority.active(t);
    // An exclusive priority step rests the rule: queue_ then waits for the next step.
    if (!(forced && params_.priority.exclusive)) {
        for (std::size_t i : queue_) {
            Site& s = sites_[i];
            s.marks &= static_cast<std::uint8_t>(~queued);
            if (s.frozen_at >= 0 || !params_.rule.freeze[s.ice_neighbours]) continue;  // forced while it waited
            if (restricted && restriction.in_region(cell_at(i))) {
                if (!(s.marks & held)) {
                    s.marks |= held;
                    held_.push_back(cell_at(i));
                }
                continue;
            }
            s.marks |= freezing;
            freezing_.push_back(i);
        }
        queue_.clear();
    }
    if (forced) force_tips();

    // Only now does the state change: every decision above saw the old one.
    // Store order is row r, then column q: ice_ comes out in ice_cells() order.
    std::sort(freezing_.begin(), freezing_.end());
    fresh_ = ice_.size();
    for (std::size_t i : freezing_) freeze_now(i, t);
    steps_ = t;
    if (radius_ + margin > half_) grow_storage();
}

void Snowflake::force_tips() {
    auto force = [&](HexCell c) {
        Site& s = sites_[index(c)];
        if (s.frozen_at >= 0 || (s.marks & freezing)) return;
        s.marks |= freezing;
        freezing_.push_back(index(c));
    };
    for (int k = 0; k < 6; ++k) {
        const int ring = arm_length(k) + 1;
        const HexCell tip = ring * hex_directions[k];
        force(tip);
        // Along the ring's two edges from the corner: step j is j lattice rows off the arm line.
        for (const HexCell along : {hex_directions[(k + 2) % 6], hex_directions[(k + 4) % 6]})
            for (int j = 1; j <= std::min(params_.priority.width, ring); ++j) {
                const HexCell c = tip + j * along;
                if (sites_[index(c)].ice_neighbours > 0) force(c);
            }
    }
}

void Snowflake::freeze_now(std::size_t i, int step) {
    Site& s = sites_[i];
    s.frozen_at = step;
    s.marks = 0;
    const HexCell c = cell_at(i);
    ice_.push_back(c);
    radius_ = std::max(radius_, hex_distance(c));
    max_distance_squared_ = std::max(max_distance_squared_, distance_squared(c));
    for (std::ptrdiff_t offset : neighbour_offsets()) ++sites_[i + static_cast<std::size_t>(offset)].ice_neighbours;
}

void Snowflake::grow_storage() {
    int half = half_;
    while (radius_ + margin > half) half *= 2;
    const std::size_t old_side = side(), new_side = 2 * static_cast<std::size_t>(half) + 1;
    const std::size_t shift = static_cast<std::size_t>(half - half_);  // old (0, 0) lands at new (shift, shift)
    std::vector<Site> bigger(new_side * new_side);
    for (std::size_t row = 0; row < old_side; ++row)
        std::copy_n(sites_.begin() + static_cast<std::ptrdiff_t>(row * old_side), old_side,
                    bigger.begin() + static_cast<std::ptrdiff_t>((row + shift) * new_side + shift));
    for (std::size_t& i : queue_) {  // cells waiting out an exclusive priority step keep their place
        const std::size_t row = i / old_side, col = i % old_side;
        i = (row + shift) * new_side + col + shift;
    }
    sites_ = std::move(bigger);
    half_ = half;
}

double Snowflake::storage_peak_bytes(int radius) {
    // grow_storage's doublings, from the first store to one that holds `radius`.
    double half = first_half, before = 0;
    while (radius + margin > half) before = half, half *= 2;
    auto sites = [](double h) { return (2 * h + 1) * (2 * h + 1); };
    return (sites(half) + (before > 0 ? sites(before) : 0)) * double(sizeof(Site));
}

std::vector<long> mass_within(const Snowflake& flake, int max_l) {
    require_integer("max_l", max_l, 0, 1000000000);
    // first[l]: ice cells whose smallest l with distance_squared <= l * l is l (the seed counts from l = 1).
    std::vector<long> first(static_cast<std::size_t>(max_l) + 1, 0);
    for (HexCell c : flake.ice_cells()) {
        const long d2 = distance_squared(c);
        long l = static_cast<long>(std::sqrt(static_cast<double>(d2)));
        while (l * l < d2) ++l;  // exact ceil(sqrt(d2)) whatever sqrt rounded to
        while (l > 0 && (l - 1) * (l - 1) >= d2) --l;
        l = std::max(l, 1L);  // the seed (l = 0) counts from l = 1; with max_l = 0 nothing is counted
        if (l <= max_l) ++first[static_cast<std::size_t>(l)];
    }
    std::vector<long> mass(static_cast<std::size_t>(max_l));
    long total = 0;
    for (int l = 1; l <= max_l; ++l)
        mass[static_cast<std::size_t>(l - 1)] = total += first[static_cast<std::size_t>(l)];
    return mass;
}

}  // namespace sim
