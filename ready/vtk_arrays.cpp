#include "ready/vtk_arrays.hpp"

#include <glib.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

namespace ready::vtk {
namespace {

// a + b and a * b, or DataError when the true result does not fit.
std::uint64_t add(std::uint64_t a, std::uint64_t b) {
    std::uint64_t sum = 0;
    if (__builtin_add_overflow(a, b, &sum)) throw DataError("an array's header gives sizes whose sum overflows");
    return sum;
}
std::uint64_t times(std::uint64_t a, std::uint64_t b) {
    std::uint64_t product = 0;
    if (__builtin_mul_overflow(a, b, &product)) throw DataError("an array's header gives sizes whose product overflows");
    return product;
}

std::string bytes_text(std::uint64_t n) { return std::to_string(n) + (n == 1 ? " byte" : " bytes"); }

void check_expected(std::uint64_t expected) {
    if (expected > max_array_bytes)
        throw DataError("an array of " + bytes_text(expected) + " is larger than figgen reads (" +
                        bytes_text(max_array_bytes) + ")");
}

void check_holds(std::uint64_t holds, std::uint64_t expected) {
    if (holds != expected)
        throw DataError("an array's header says it holds " + bytes_text(holds) + "; its extent needs " +
                        bytes_text(expected));
}

// The header word at `p`, which has at least `size` bytes.
std::uint64_t word(const std::uint8_t* p, int size) {
    if (size == 4) {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    std::uint64_t v;
    std::memcpy(&v, p, 8);
    return v;
}

// The characters that hold `bytes` bytes in base64 (padded). `bytes` is
// at most max_array_bytes plus a header, so this cannot wrap.
std::size_t base64_chars(std::uint64_t bytes) { return static_cast<std::size_t>((bytes + 2) / 3 * 4); }

std::vector<std::uint8_t> base64(std::string_view text) {
    if (text.size() % 4 != 0)
        throw DataError("base64 data of " + std::to_string(text.size()) + " characters, not a multiple of 4");
    for (char c : text)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/' || c == '='))
            throw DataError("base64 data holds a character outside base64");
    const std::string terminated(text);  // GLib reads up to a NUL
    gsize length = 0;
    guchar* bytes = g_base64_decode(terminated.c_str(), &length);
    std::vector<std::uint8_t> out(bytes, bytes + length);
    g_free(bytes);
    return out;
}

// The compressed blocks' header: their count, the size of each but the
// last, the last one's size (0: a whole block), and each one's compressed
// size. Every number is checked here, against `expected` and `available`
// (the compressed bytes there are after the header), before any is used.
struct Blocks {
    std::uint64_t count = 0, size = 0, last = 0;
    std::vector<std::uint64_t> compressed;
    std::uint64_t total_compressed = 0;

    std::uint64_t inflated(std::uint64_t i) const { return i + 1 == count && last ? last : size; }
};

// The words of a compressed array's header that come before its sizes.
constexpr std::uint64_t leading_words = 3;

std::uint64_t block_count(const std::uint8_t* p, std::size_t available, int header) {
    if (available < leading_words * static_cast<std::uint64_t>(header))
        throw DataError("a compressed array's header is cut short");
    const std::uint64_t count = word(p, header);
    // Blocks of at most 1 GiB each, 2^20 of them at most: far past any array figgen reads.
    if (count > (std::uint64_t{1} << 20)) throw DataError("a compressed array's header gives more than 2^20 blocks");
    return count;
}

// The header's bytes: three words and one per block.
std::uint64_t header_bytes(std::uint64_t count, int header) {
    return times(add(leading_words, count), static_cast<std::uint64_t>(header));
}

Blocks read_blocks(const std::uint8_t* p, std::size_t available, int header, std::uint64_t expected) {
    Blocks b;
    b.count = block_count(p, available, header);
    b.size = word(p + header, header);
    b.last = word(p + 2 * header, header);
    if (b.count > 0 && (b.size == 0 || b.size > (std::uint64_t{1} << 30)))
        throw DataError("a compressed array's block size is " + bytes_text(b.size) + ", not from 1 byte to 1 GiB");
    if (b.last > b.size)
        throw DataError("a compressed array's last block is " + bytes_text(b.last) + ", more than its block size");
    const std::uint64_t holds =
        b.count == 0 ? 0 : add(times(b.count - 1, b.size), b.last ? b.last : b.size);
    check_holds(holds, expected);
    if (available < header_bytes(b.count, header)) throw DataError("a compressed array's header is cut short");
    b.compressed.reserve(static_cast<std::size_t>(b.count));
    for (std::uint64_t i = 0; i < b.count; ++i) {
        const std::uint64_t size = word(p + (leading_words + i) * header, header);
        // zlib's bound on what a block of this size compresses to: no
        // honest writer makes a block larger, and it keeps the sum small.
        if (size > compressBound(static_cast<uLong>(b.inflated(i))))
            throw DataError("a compressed block's size is " + bytes_text(size) + ", more than zlib makes of " +
                            bytes_text(b.inflated(i)));
        b.compressed.push_back(size);
        b.total_compressed = add(b.total_compressed, size);
    }
    return b;
}

std::vector<std::uint8_t> inflate(const Blocks& b, const std::uint8_t* data, std::size_t available,
                                  std::uint64_t expected) {
    if (b.total_compressed > available)
        throw DataError("a compressed array is cut short: its header gives " + bytes_text(b.total_compressed) +
                        ", " + bytes_text(available) + " follow");
    std::vector<std::uint8_t> out(static_cast<std::size_t>(expected));
    std::uint64_t at = 0, from = 0;
    for (std::uint64_t i = 0; i < b.count; ++i) {
        const std::uint64_t want = b.inflated(i);
        // Both hold by the checks above; checked again where the pointers are made.
        if (add(at, want) > out.size() || add(from, b.compressed[i]) > available)
            throw DataError("a compressed array's blocks do not fit its data");
        uLongf got = static_cast<uLongf>(want);
        if (uncompress(out.data() + at, &got, data + from, static_cast<uLong>(b.compressed[i])) != Z_OK || got != want)
            throw DataError("a compressed block does not inflate to its size");
        at += want;
        from += b.compressed[i];
    }
    return out;
}

std::string without_space(std::string_view spaced) {
    std::string kept;
    kept.reserve(spaced.size());
    for (char c : spaced)
        if (!std::isspace(static_cast<unsigned char>(c))) kept.push_back(c);
    return kept;
}

}  // namespace

std::vector<std::uint8_t> decode_base64(std::string_view spaced, const Encoding& e, std::uint64_t expected) {
    check_expected(expected);
    const std::string kept = without_space(spaced);  // VTK, or an editor, may have put space in it
    const std::string_view text = kept;
    const auto header = static_cast<std::uint64_t>(e.header);
    if (!e.compressed) {
        const std::size_t head = base64_chars(header);
        if (text.size() < head) throw DataError("an array's header is cut short");
        // Padding ('=') among the header's characters decodes to fewer bytes than the word.
        const std::vector<std::uint8_t> words = base64(text.substr(0, head));
        if (words.size() < header) throw DataError("an array's header is cut short");
        check_holds(word(words.data(), e.header), expected);
        const std::size_t chars = base64_chars(header + expected);
        if (text.size() < chars) throw DataError("an array is cut short");
        const std::vector<std::uint8_t> all = base64(text.substr(0, chars));
        if (all.size() < header + expected) throw DataError("an array is cut short");
        return {all.begin() + e.header, all.begin() + static_cast<std::ptrdiff_t>(header + expected)};
    }
    // The header is base64 of its own, the data after it another.
    const std::size_t first = base64_chars(leading_words * header);
    if (text.size() < first) throw DataError("a compressed array's header is cut short");
    const std::vector<std::uint8_t> start = base64(text.substr(0, first));
    const std::uint64_t count = block_count(start.data(), start.size(), e.header);
    const std::size_t head = base64_chars(header_bytes(count, e.header));
    if (text.size() < head) throw DataError("a compressed array's header is cut short");
    const std::vector<std::uint8_t> words = base64(text.substr(0, head));
    const Blocks b = read_blocks(words.data(), words.size(), e.header, expected);
    // The data's characters, checked against those there before the
    // count is turned into characters.
    if (b.total_compressed > (text.size() - head) / 4 * 3)
        throw DataError("a compressed array is cut short: its header gives " + bytes_text(b.total_compressed));
    const std::size_t chars = base64_chars(b.total_compressed);
    const std::vector<std::uint8_t> data = base64(text.substr(head, chars));
    return inflate(b, data.data(), data.size(), expected);
}

std::vector<std::uint8_t> decode_raw(std::string_view bytes, const Encoding& e, std::uint64_t expected) {
    check_expected(expected);
    const auto* p = reinterpret_cast<const std::uint8_t*>(bytes.data());
    const auto header = static_cast<std::size_t>(e.header);
    if (!e.compressed) {
        if (bytes.size() < header) throw DataError("an array's header is cut short");
        check_holds(word(p, e.header), expected);
        if (bytes.size() - header < expected) throw DataError("an array is cut short");
        return {p + header, p + header + expected};
    }
    const Blocks b = read_blocks(p, bytes.size(), e.header, expected);
    const auto head = static_cast<std::size_t>(header_bytes(b.count, e.header));  // <= bytes.size(), read_blocks checked
    return inflate(b, p + head, bytes.size() - head, expected);
}

std::vector<double> decode_ascii(std::string_view text, std::uint64_t count, bool float64) {
    check_expected(times(count, 8));
    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(count, text.size() / 2 + 1)));
    const char* at = text.data();
    const char* const end = text.data() + text.size();
    const auto skip_space = [&] {
        while (at < end && std::isspace(static_cast<unsigned char>(*at))) ++at;
    };
    for (skip_space(); at < end; skip_space()) {
        if (values.size() == count) throw DataError("an ascii array holds more than " + std::to_string(count) + " numbers");
        double v = 0;
        const char* from = at + (*at == '+' ? 1 : 0);  // from_chars takes no '+'
        const auto [next, ec] = std::from_chars(from, end, v);
        if (ec != std::errc() || (next < end && !std::isspace(static_cast<unsigned char>(*next))))
            throw DataError("an ascii array holds something other than numbers");
        values.push_back(float64 ? v : static_cast<float>(v));
        at = next;
    }
    if (values.size() != count)
        throw DataError("an ascii array holds " + std::to_string(values.size()) + " numbers, not " + std::to_string(count));
    return values;
}

std::vector<double> numbers_of(const std::vector<std::uint8_t>& bytes, bool float64) {
    std::vector<double> out(bytes.size() / (float64 ? 8 : 4));
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (float64) {
            std::memcpy(&out[i], bytes.data() + 8 * i, 8);
        } else {
            float f;
            std::memcpy(&f, bytes.data() + 4 * i, 4);
            out[i] = f;
        }
    }
    return out;
}

namespace {

// `bytes` in zlib blocks of 32 KiB with UInt64 headers, base64.
std::string zlib_base64(const std::vector<std::uint8_t>& bytes) {
    const std::uint64_t block = 32768;
    const std::uint64_t count = (bytes.size() + block - 1) / block;
    // VTK's header: the blocks, their size, the last one's when it is shorter (else 0), each compressed size.
    std::vector<std::uint64_t> header = {count, block, bytes.size() % block};
    // Each block compressed on its own (side by side on the run's threads:
    // a 128^3 state is 256 of them), then laid end to end in order.
    std::vector<std::vector<std::uint8_t>> blocks(static_cast<std::size_t>(count));
    bool failed = false;
#pragma omp parallel for schedule(dynamic, 4) reduction(|| : failed)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(count); ++i) {
        const std::size_t from = static_cast<std::size_t>(i) * block;
        const std::size_t n = std::min<std::size_t>(block, bytes.size() - from);
        std::vector<std::uint8_t>& out = blocks[static_cast<std::size_t>(i)];
        uLongf size = compressBound(static_cast<uLong>(n));
        out.resize(size);
        // zlib's fastest level: a 128^3 state of floats (16 MiB) in 0.25 s
        // of CPU against 0.37 at VTK's 5, for 0.3% more bytes.
        if (compress2(out.data(), &size, bytes.data() + from, static_cast<uLong>(n), Z_BEST_SPEED) != Z_OK)
            failed = true;
        out.resize(size);
    }
    if (failed) throw std::runtime_error("zlib could not compress an array");
    std::vector<std::uint8_t> data;
    for (const auto& out : blocks) {
        header.push_back(out.size());
        data.insert(data.end(), out.begin(), out.end());
    }
    const auto encode = [](const void* p, std::size_t n) {
        gchar* text = g_base64_encode(static_cast<const guchar*>(p), n);
        std::string s(text);
        g_free(text);
        return s;
    };
    return encode(header.data(), header.size() * 8) + encode(data.data(), data.size());
}

}  // namespace

std::string encode_zlib_base64(const std::vector<double>& values, bool float64) {
    std::vector<std::uint8_t> bytes(values.size() * (float64 ? 8 : 4));
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (float64) {
            std::memcpy(bytes.data() + 8 * i, &values[i], 8);
        } else {
            const float f = static_cast<float>(values[i]);
            std::memcpy(bytes.data() + 4 * i, &f, 4);
        }
    }
    return zlib_base64(bytes);
}

// --- integer arrays ----------------------------------------------------------

namespace {

// The least and most values of `type`, as int64 (UInt64's most: int64's, all figgen keeps).
std::int64_t least(IntegerType t) {
    if (!t.is_signed) return 0;
    if (t.bytes == 8) return std::numeric_limits<std::int64_t>::min();
    return -(std::int64_t{1} << (8 * t.bytes - 1));
}
std::int64_t most(IntegerType t) {
    if (t.bytes == 8) return std::numeric_limits<std::int64_t>::max();
    return t.is_signed ? (std::int64_t{1} << (8 * t.bytes - 1)) - 1 : (std::int64_t{1} << (8 * t.bytes)) - 1;
}

}  // namespace

std::optional<IntegerType> integer_type(std::string_view name) {
    static const std::pair<std::string_view, IntegerType> types[] = {
        {"Int8", {1, true}},   {"UInt8", {1, false}},  {"Int16", {2, true}}, {"UInt16", {2, false}},
        {"Int32", {4, true}},  {"UInt32", {4, false}}, {"Int64", {8, true}}, {"UInt64", {8, false}}};
    for (const auto& [n, t] : types)
        if (n == name) return t;
    return std::nullopt;
}

std::vector<std::int64_t> integers_of(const std::vector<std::uint8_t>& bytes, IntegerType t) {
    const auto size = static_cast<std::size_t>(t.bytes);
    std::vector<std::int64_t> out(bytes.size() / size);
    for (std::size_t i = 0; i < out.size(); ++i) {
        std::uint64_t u = 0;
        std::memcpy(&u, bytes.data() + size * i, size);  // little-endian: the low bytes
        if (t.is_signed && size < 8 && (u >> (8 * size - 1)) != 0) u |= ~std::uint64_t{0} << (8 * size);  // the sign, extended
        if (!t.is_signed && size == 8 && u > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
            throw DataError("a UInt64 array holds a value past 2^63 - 1");
        out[i] = static_cast<std::int64_t>(u);
    }
    return out;
}

std::vector<std::int64_t> decode_ascii_integers(std::string_view text, std::uint64_t count, IntegerType t) {
    check_expected(times(count, 8));
    std::vector<std::int64_t> values;
    values.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(count, text.size() / 2 + 1)));
    const char* at = text.data();
    const char* const end = text.data() + text.size();
    const auto skip_space = [&] {
        while (at < end && std::isspace(static_cast<unsigned char>(*at))) ++at;
    };
    for (skip_space(); at < end; skip_space()) {
        if (values.size() == count) throw DataError("an ascii array holds more than " + std::to_string(count) + " numbers");
        std::int64_t v = 0;
        const char* from = at + (*at == '+' ? 1 : 0);  // from_chars takes no '+'
        const auto [next, ec] = std::from_chars(from, end, v);
        if (ec == std::errc::result_out_of_range || (ec == std::errc() && (v < least(t) || v > most(t))))
            throw DataError("an ascii array holds a number outside its type (" + std::to_string(least(t)) + " to " +
                            std::to_string(most(t)) + ")");
        if (ec != std::errc() || (next < end && !std::isspace(static_cast<unsigned char>(*next))))
            throw DataError("an ascii array holds something other than integers");
        values.push_back(v);
        at = next;
    }
    if (values.size() != count)
        throw DataError("an ascii array holds " + std::to_string(values.size()) + " numbers, not " + std::to_string(count));
    return values;
}

std::string encode_zlib_base64_integers(const std::vector<std::int64_t>& values, IntegerType t) {
    const auto size = static_cast<std::size_t>(t.bytes);
    std::vector<std::uint8_t> bytes(values.size() * size);
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (values[i] < least(t) || values[i] > most(t))
            throw std::invalid_argument("encode_zlib_base64_integers: " + std::to_string(values[i]) +
                                        " is outside the array's type");
        const auto u = static_cast<std::uint64_t>(values[i]);
        std::memcpy(bytes.data() + size * i, &u, size);  // little-endian: the low bytes
    }
    return zlib_base64(bytes);
}

}  // namespace ready::vtk
