#pragma once
// SHA-256 (OpenSSL's libcrypto), as lowercase hex: the hash of a
// model's state in the metadata and of decoded pixels in the image tests.

#include <cstddef>
#include <string>

namespace base {

std::string sha256_hex(const void* data, std::size_t size);

}  // namespace base
