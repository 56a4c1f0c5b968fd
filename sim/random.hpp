#pragma once
// figgen's one source of randomness: xoshiro256** 1.0 (Blackman & Vigna,
// 2018), its 256-bit state filled from the 64-bit seed by SplitMix64, as the
// authors recommend. Every draw in every model comes from here, so the same
// seed gives the same bits with any compiler or standard library
// (std::uniform_*_distribution is not portable and is never used).

#include <array>
#include <cstdint>

namespace sim {

// SplitMix64 (Steele, Lea & Flood 2014): expands a seed into well-mixed words.
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next();

private:
    std::uint64_t state_;
};

class Random {
public:
    explicit Random(std::uint64_t seed);
    // The stream of work item `item` of a run seeded `seed`: its state is
    // filled by SplitMix64 from a counter that mixes both (the item's key
    // through SplitMix64's finaliser, added to the seed's). It depends on
    // (seed, item) only, never on which thread, rank or shard draws it, so a
    // figure split into items gives the same bits however it is run.
    static Random for_item(std::uint64_t seed, std::uint64_t item);
    // A generator resuming from a saved state (not all zero).
    static Random from_state(const std::array<std::uint64_t, 4>& state);
    std::array<std::uint64_t, 4> state() const { return {s_[0], s_[1], s_[2], s_[3]}; }

    std::uint64_t next();  // 64 random bits
    // Uniform in [0, 1): the top 53 bits of next() times 2^-53, so every
    // value is a multiple of 2^-53 and 1.0 is never returned.
    double uniform();
    double uniform(double low, double high) { return low + (high - low) * uniform(); }
    // Uniform integer in [0, n), n > 0, unbiased: draws with a value in the
    // incomplete last block of 2^64 mod n are rejected and redrawn.
    std::uint64_t below(std::uint64_t n);

private:
    Random() = default;
    std::uint64_t s_[4];
};

}  // namespace sim
