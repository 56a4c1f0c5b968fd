#include "base/digest.hpp"

extern "C" {
#include <libavutil/mem.h>
#include <libavutil/sha.h>
}

#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>

namespace base {

std::string sha256_hex(const void* data, std::size_t size) {
    std::unique_ptr<AVSHA, decltype(&av_free)> sha(av_sha_alloc(), &av_free);
    if (!sha || av_sha_init(sha.get(), 256) < 0) throw std::runtime_error("sha256: cannot initialise");
    av_sha_update(sha.get(), static_cast<const std::uint8_t*>(data), size);
    std::uint8_t digest[32];
    av_sha_final(sha.get(), digest);
    std::string hex(64, '0');
    for (int i = 0; i < 32; ++i) std::snprintf(&hex[2 * i], 3, "%02x", digest[i]);
    return hex;
}

}  // namespace base
