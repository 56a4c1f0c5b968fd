#include "description/integer_text.hpp"

#include <charconv>
#include <system_error>

namespace description {

std::optional<long long> integer_text(std::string_view text, long long low, long long high) {
    // from_chars takes no space and no '+', and says when the digits overflow.
    long long value = 0;
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value, 10);
    if (text.empty() || error != std::errc() || stop != end || value < low || value > high) return std::nullopt;
    return value;
}

}  // namespace description
