#include "base/digest.hpp"

#include <openssl/evp.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

namespace base {

namespace {

std::string hex_of(const unsigned char* digest, unsigned int length) {
    if (length != 32) throw std::runtime_error("sha256: OpenSSL gave a digest of " + std::to_string(length) + " bytes");
    std::string hex(64, '0');
    for (int i = 0; i < 32; ++i) std::snprintf(&hex[2 * i], 3, "%02x", digest[i]);
    return hex;
}

}  // namespace

std::string sha256_hex(const void* data, std::size_t size) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    if (EVP_Digest(data, size, digest, &length, EVP_sha256(), nullptr) != 1)
        throw std::runtime_error("sha256: OpenSSL's EVP_Digest failed");
    return hex_of(digest, length);
}

std::string sha256_hex(std::span<const Bytes> pieces) {
    const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> context(EVP_MD_CTX_new(), EVP_MD_CTX_free);
    bool ok = context && EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr) == 1;
    for (const Bytes& piece : pieces) ok = ok && EVP_DigestUpdate(context.get(), piece.data, piece.size) == 1;
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    if (!ok || EVP_DigestFinal_ex(context.get(), digest, &length) != 1)
        throw std::runtime_error("sha256: OpenSSL's EVP_Digest failed");
    return hex_of(digest, length);
}

}  // namespace base
