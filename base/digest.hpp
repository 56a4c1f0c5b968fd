#pragma once
// SHA-256 (OpenSSL's libcrypto), as lowercase hex: the hash of a
// model's state in the metadata and of decoded pixels in the image tests.

#include <cstddef>
#include <span>
#include <string>

namespace base {

std::string sha256_hex(const void* data, std::size_t size);

// A piece of memory to hash.
struct Bytes {
    const void* data;
    std::size_t size;
};

// The hash of the pieces laid end to end (without copying them together).
std::string sha256_hex(std::span<const Bytes> pieces);

}  // namespace base
