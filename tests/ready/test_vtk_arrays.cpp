// VTK's data arrays (ready/vtk_arrays.cpp): what figgen writes reads back
// to the same values, and a header that lies (sizes that wrap past 2^64,
// more blocks or bytes than there are) is refused before anything is read
// from where it points.
#include <catch2/catch.hpp>

#include <glib.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "ready/vtk_arrays.hpp"

using ready::vtk::DataError;
using ready::vtk::Encoding;

namespace {

std::string as_bytes(const std::vector<std::uint64_t>& words) {
    std::string s(words.size() * 8, '\0');
    std::memcpy(s.data(), words.data(), s.size());
    return s;
}

std::string base64(const std::string& bytes) {
    gchar* text = g_base64_encode(reinterpret_cast<const guchar*>(bytes.data()), bytes.size());
    std::string s(text);
    g_free(text);
    return s;
}

std::string compressed(const std::string& bytes) {
    uLongf size = compressBound(static_cast<uLong>(bytes.size()));
    std::string out(size, '\0');
    REQUIRE(compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(bytes.data()),
                      static_cast<uLong>(bytes.size()), 6) == Z_OK);
    out.resize(size);
    return out;
}

// 64 bytes in two zlib blocks of 32, with UInt64 headers: the header's
// words and the data, so that a test can make the header lie.
struct TwoBlocks {
    std::string first = compressed(std::string(32, '\x11')), second = compressed(std::string(32, '\x22'));
    std::vector<std::uint64_t> header() const { return {2, 32, 0, first.size(), second.size()}; }
    std::string data() const { return first + second; }
};

std::string refusal_raw(const std::string& bytes, std::uint64_t expected, Encoding e = {8, true}) {
    try {
        ready::vtk::decode_raw(bytes, e, expected);
    } catch (const DataError& error) {
        return error.what();
    }
    return "(decoded)";
}

std::string refusal_base64(const std::string& text, std::uint64_t expected, Encoding e = {8, true}) {
    try {
        ready::vtk::decode_base64(text, e, expected);
    } catch (const DataError& error) {
        return error.what();
    }
    return "(decoded)";
}

}  // namespace

TEST_CASE("an array figgen encodes decodes to the same values", "[ready][vtk]") {
    std::vector<double> values(20000);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.001 * static_cast<double>(i) - 3.25;
    for (bool float64 : {false, true}) {
        const std::string text = ready::vtk::encode_zlib_base64(values, float64);
        const std::uint64_t bytes = values.size() * (float64 ? 8 : 4);
        const auto back = ready::vtk::numbers_of(ready::vtk::decode_base64(text, {8, true}, bytes), float64);
        REQUIRE(back.size() == values.size());
        for (std::size_t i = 0; i < values.size(); ++i)
            CHECK(back[i] == (float64 ? values[i] : static_cast<double>(static_cast<float>(values[i]))));
    }
    // And the two blocks made here, raw and as base64 (header and data apart, as VTK writes them).
    const TwoBlocks b;
    const auto raw = ready::vtk::decode_raw(as_bytes(b.header()) + b.data(), {8, true}, 64);
    REQUIRE(raw.size() == 64);
    CHECK(raw[0] == 0x11);
    CHECK(raw[31] == 0x11);
    CHECK(raw[32] == 0x22);
    CHECK(raw[63] == 0x22);
    CHECK(ready::vtk::decode_base64(base64(as_bytes(b.header())) + "\n  " + base64(b.data()), {8, true}, 64) == raw);
}

TEST_CASE("block sizes that add up past 2^64 are refused, not followed", "[ready][vtk]") {
    // Issue 46's file: sizes 2^63 and 2^63 + L, which wrap to L, the data
    // there is: an unchecked sum passes, and the first block is read 2^63
    // bytes long.
    const TwoBlocks b;
    const std::uint64_t half = std::uint64_t{1} << 63;
    const std::uint64_t total = b.first.size() + b.second.size();
    const std::vector<std::uint64_t> lying = {2, 32, 0, half, half + total};
    using Catch::Contains;
    CHECK_THAT(refusal_raw(as_bytes(lying) + b.data(), 64), Contains("a compressed block's size is 9223372036854775808 bytes"));
    CHECK_THAT(refusal_base64(base64(as_bytes(lying)) + base64(b.data()), 64), Contains("more than zlib makes of 32 bytes"));
    // Each size within zlib's bound, their sum past what follows.
    const std::vector<std::uint64_t> long_sizes = {2, 32, 0, compressBound(32), compressBound(32)};
    CHECK_THAT(refusal_raw(as_bytes(long_sizes) + b.data(), 64), Contains("a compressed array is cut short"));
    CHECK_THAT(refusal_base64(base64(as_bytes(long_sizes)) + base64(b.data()), 64), Contains("cut short"));
}

TEST_CASE("a header that lies about counts or sizes is refused in words", "[ready][vtk]") {
    const TwoBlocks b;
    using Catch::Contains;
    CHECK_THAT(refusal_raw(as_bytes({std::uint64_t{1} << 40, 32, 0}) + b.data(), 64), Contains("more than 2^20 blocks"));
    CHECK_THAT(refusal_raw(as_bytes({2, 32, 0, 10}), 64), Contains("header is cut short"));
    CHECK_THAT(refusal_raw(as_bytes({2, 0, 0, 10, 10}), 64), Contains("block size is 0 bytes"));
    CHECK_THAT(refusal_raw(as_bytes({2, 32, 33, 10, 10}), 64), Contains("last block is 33 bytes, more than its block size"));
    CHECK_THAT(refusal_raw(as_bytes({2, 32, 0, 10, 10}), 96), Contains("holds 64 bytes; its extent needs 96 bytes"));
    // The most blocks of the largest size: far past the extent, refused before any size is read.
    CHECK_THAT(refusal_raw(as_bytes({1u << 20, std::uint64_t{1} << 30, 0}), 64),
               Contains("holds 1125899906842624 bytes; its extent needs 64 bytes"));
    CHECK_THAT(refusal_raw(as_bytes(b.header()) + b.data().substr(0, 20), 64), Contains("cut short"));
    std::string damaged = as_bytes(b.header()) + b.data();
    damaged[40 + 3] ^= 0x5a;
    CHECK_THAT(refusal_raw(damaged, 64), Contains("does not inflate to its size"));
    // Uncompressed: a 32-bit header, then the bytes.
    std::string plain(4, '\0');
    const std::uint32_t sixteen = 16;
    std::memcpy(plain.data(), &sixteen, 4);
    CHECK(ready::vtk::decode_raw(plain + std::string(16, 'x'), {4, false}, 16).size() == 16);
    CHECK_THAT(refusal_raw(plain + std::string(15, 'x'), 16, {4, false}), Contains("an array is cut short"));
    CHECK_THAT(refusal_raw(plain + std::string(16, 'x'), 20, {4, false}), Contains("holds 16 bytes; its extent needs 20"));
    CHECK_THAT(refusal_base64("AAAA", 16, {4, false}), Contains("an array's header is cut short"));
    CHECK_THAT(refusal_base64("EAAAAA==", 16, {4, false}), Contains("an array is cut short"));
    // Padding inside the header's twelve characters: they decode to 7 bytes, not the 8 of its word
    // (a fuzzer's find: the word was read past them).
    CHECK_THAT(refusal_base64("AAAAAAAAAA==AAAAAAAAAAAA", 8, {8, false}), Contains("an array's header is cut short"));
    CHECK_THAT(refusal_base64("EAAA*AAA", 16, {4, false}), Contains("a character outside base64"));
    // More than figgen reads at all.
    CHECK_THAT(refusal_raw("", std::uint64_t{1} << 40), Contains("larger than figgen reads"));
}

TEST_CASE("ascii arrays hold exactly their numbers", "[ready][vtk]") {
    CHECK(ready::vtk::decode_ascii(" 1 -2.5\n+3e2 ", 3, true) == std::vector<double>{1, -2.5, 300});
    CHECK(ready::vtk::decode_ascii("0.1", 1, false)[0] == static_cast<double>(0.1f));
    using Catch::Contains;
    const auto refusal = [](const std::string& text, std::uint64_t count) -> std::string {
        try {
            ready::vtk::decode_ascii(text, count, true);
        } catch (const DataError& e) {
            return e.what();
        }
        return "(decoded)";
    };
    CHECK_THAT(refusal("1 2", 3), Contains("holds 2 numbers, not 3"));
    CHECK_THAT(refusal("1 2 3 4", 3), Contains("more than 3 numbers"));
    CHECK_THAT(refusal("1 x 3", 3), Contains("something other than numbers"));
    CHECK_THAT(refusal("1 2e 3", 3), Contains("something other than numbers"));
}
