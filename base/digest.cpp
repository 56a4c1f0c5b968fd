#include "base/digest.hpp"

#include <openssl/evp.h>

#include <cstdint>
#include <cstdio>
#include <stdexcept>

namespace base {

std::string sha256_hex(const void* data, std::size_t size) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    if (EVP_Digest(data, size, digest, &length, EVP_sha256(), nullptr) != 1 || length != 32)
        throw std::runtime_error("sha256: OpenSSL's EVP_Digest failed");
    std::string hex(64, '0');
    for (int i = 0; i < 32; ++i) std::snprintf(&hex[2 * i], 3, "%02x", digest[i]);
    return hex;
}

}  // namespace base
