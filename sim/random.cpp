#include "sim/random.hpp"

#include <stdexcept>

namespace sim {
namespace {

constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

std::uint64_t SplitMix64::next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

Random::Random(std::uint64_t seed) {
    SplitMix64 mix(seed);
    for (auto& word : s_) word = mix.next();  // never all zero: SplitMix64 is a bijection of distinct counters
}

Random Random::for_item(std::uint64_t seed, std::uint64_t item) {
    // Two independent-looking words, one from each input, summed: distinct
    // (seed, item) pairs give distinct counters but with probability ~2^-64.
    const std::uint64_t counter = SplitMix64(seed).next() + SplitMix64(~item).next();
    Random r;
    SplitMix64 mix(counter);
    for (auto& word : r.s_) word = mix.next();
    return r;
}

Random Random::from_state(const std::array<std::uint64_t, 4>& state) {
    if (state[0] == 0 && state[1] == 0 && state[2] == 0 && state[3] == 0)
        throw std::invalid_argument("xoshiro256** state must not be all zero");
    Random r;
    for (int i = 0; i < 4; ++i) r.s_[i] = state[i];
    return r;
}

std::uint64_t Random::next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
}

double Random::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

std::uint64_t Random::below(std::uint64_t n) {
    // 2^64 mod n, computed without 128-bit arithmetic.
    const std::uint64_t threshold = (0 - n) % n;
    for (;;) {
        const std::uint64_t x = next();
        if (x >= threshold) return x % n;  // [threshold, 2^64) holds a whole number of blocks of n
    }
}

}  // namespace sim
