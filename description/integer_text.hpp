#pragma once
// Integers a person types (an option's value, a part of "1200x600" or
// "2/8"): decimal digits with an optional leading '-', nothing else: no
// space, '+', exponent or fraction. Parsed into a range checked before the
// value is narrowed, so "4294967396" is refused, never read as 100.

#include <optional>
#include <string_view>

namespace description {

// `text` as such an integer within [low, high]; none for anything else.
std::optional<long long> integer_text(std::string_view text, long long low, long long high);

}  // namespace description
