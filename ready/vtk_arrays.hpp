#pragma once
// VTK XML's data arrays, as the file holds them: decoded from each
// encoding VTK writes (ascii; binary as base64; appended as base64 or raw
// bytes; raw or zlib-compressed in blocks, with 32- or 64-bit headers) and
// encoded as VTK 9 writes Ready's files (base64, zlib blocks, 64-bit
// headers).
//
// A file is a stranger's: every size, count and offset its headers give is
// checked against the bytes that remain before it is used, in arithmetic
// that cannot wrap, so nothing a file says makes figgen read outside the
// buffer it holds. base64 by GLib, zlib by zlib.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace ready::vtk {

// What is wrong with an array, in words that quote nothing of the file.
struct DataError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// How a file stores its arrays: <VTKFile header_type> and <VTKFile compressor>.
struct Encoding {
    int header = 4;           // bytes of a header word: 4 (UInt32) or 8 (UInt64)
    bool compressed = false;  // zlib blocks (vtkZLibDataCompressor)
};

// The most bytes an array may decode to: a file can say more, zlib can
// make far more of a small file, and neither is taken on trust.
inline constexpr std::uint64_t max_array_bytes = std::uint64_t{1} << 31;

// The bytes of an array of `expected` bytes whose data begins at its
// header: base64 text (binary, or appended base64 from its offset;
// whitespace anywhere) or raw bytes (appended raw). Throws DataError when
// the header does not give `expected` bytes or the data is cut short,
// damaged or larger than max_array_bytes.
std::vector<std::uint8_t> decode_base64(std::string_view text, const Encoding& encoding, std::uint64_t expected);
std::vector<std::uint8_t> decode_raw(std::string_view bytes, const Encoding& encoding, std::uint64_t expected);

// `count` numbers written out as text (format="ascii"); each rounded to
// float unless `float64`. Throws DataError for anything else there.
std::vector<double> decode_ascii(std::string_view text, std::uint64_t count, bool float64);

// Little-endian Float32 or Float64 values as doubles.
std::vector<double> numbers_of(const std::vector<std::uint8_t>& bytes, bool float64);

// `values` as Float32 (or Float64) in zlib blocks of 32 KiB with UInt64
// headers, base64: the text of a binary DataArray as VTK 9 writes it.
std::string encode_zlib_base64(const std::vector<double>& values, bool float64);

// --- integer arrays (a mesh's cells: connectivity, offsets, types, faces) ---

// One of VTK's integer types (<DataArray type>: Int8 to UInt64).
struct IntegerType {
    int bytes = 8;
    bool is_signed = true;
};

// The integer type `name` names; none for any other name.
std::optional<IntegerType> integer_type(std::string_view name);

// Little-endian integers of `type` as int64. Throws DataError for a UInt64
// past int64's range.
std::vector<std::int64_t> integers_of(const std::vector<std::uint8_t>& bytes, IntegerType type);

// `count` integers of `type` written out as text (format="ascii"). Throws
// DataError for anything else there, or a number outside the type.
std::vector<std::int64_t> decode_ascii_integers(std::string_view text, std::uint64_t count, IntegerType type);

// `values` as `type`, in zlib blocks as encode_zlib_base64 makes them.
// Throws std::invalid_argument for a value the type cannot hold.
std::string encode_zlib_base64_integers(const std::vector<std::int64_t>& values, IntegerType type);

}  // namespace ready::vtk
