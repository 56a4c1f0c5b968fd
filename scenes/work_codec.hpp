#pragma once
// Numbers in a work item's result (scenes/work_items.hpp): arrays of floats or
// doubles as one CBOR byte string each, in the host's byte order (the ranks
// and shards of a run share a machine type), read back with their size
// checked, since a merge reads parts that came from elsewhere.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace scenes {

template <class T>
nlohmann::json binary_of(std::span<const T> values) {
    std::vector<std::uint8_t> bytes(values.size() * sizeof(T));
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return nlohmann::json::binary(std::move(bytes));
}

// The `count` values of `j` (binary_of's); std::runtime_error for anything else.
template <class T>
std::vector<T> values_of(const nlohmann::json& j, std::size_t count) {
    if (!j.is_binary() || j.get_binary().size() != count * sizeof(T))
        throw std::runtime_error("a work item's result holds " +
                                 (j.is_binary() ? std::to_string(j.get_binary().size()) + " bytes" : "no array") +
                                 " where " + std::to_string(count * sizeof(T)) + " were expected");
    std::vector<T> values(count);
    if (count) std::memcpy(values.data(), j.get_binary().data(), count * sizeof(T));
    return values;
}

// Checks of a result read back from a part (WorkItems::check_result). Each
// throws std::invalid_argument naming the key and what it holds instead.
namespace result_check {

// "1e+30", "NaN": a number as the messages quote it.
inline std::string quoted(double value) {
    if (std::isnan(value)) return "NaN";
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

inline std::string range(double low, double high) {
    std::string text = "[";  // appended in steps: GCC 12 warns (-Wrestrict) of a false overlap in "[" + ...
    text += quoted(low);
    text += ", ";
    text += quoted(high);
    return text += "]";
}

// `r`'s member `key`, which must be there.
inline const nlohmann::json& member(const nlohmann::json& r, const std::string& key) {
    if (!r.is_object()) throw std::invalid_argument("the result is not a map of keys");
    const auto it = r.find(key);
    if (it == r.end()) throw std::invalid_argument("the result has no " + key);
    return *it;
}

// A finite number in [low, high].
inline double number_in(const nlohmann::json& value, const std::string& key, double low, double high) {
    if (!value.is_number()) throw std::invalid_argument(key + " is not a number");
    const double v = value.get<double>();
    if (!std::isfinite(v) || v < low || v > high)
        throw std::invalid_argument(key + " holds " + quoted(v) + ", outside " + range(low, high));
    return v;
}

// An integer in [low, high], without wrapping (2^63 is not 0).
inline long long integer_in(const nlohmann::json& value, const std::string& key, long long low, long long high) {
    const bool fits = value.is_number_integer() &&
                      (!value.is_number_unsigned() ||
                       value.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<long long>::max()));
    if (!fits) throw std::invalid_argument(key + " is not an integer of at most 63 bits");
    const long long v = value.get<long long>();
    if (v < low || v > high)
        throw std::invalid_argument(key + " holds " + std::to_string(v) + ", outside [" + std::to_string(low) + ", " +
                                    std::to_string(high) + "]");
    return v;
}

inline bool boolean(const nlohmann::json& value, const std::string& key) {
    if (!value.is_boolean()) throw std::invalid_argument(key + " is not true or false");
    return value.get<bool>();
}

// An array of `count` entries (any count when `count` < 0).
inline const nlohmann::json& array_of(const nlohmann::json& value, const std::string& key, long long count) {
    if (!value.is_array()) throw std::invalid_argument(key + " is not an array");
    if (count >= 0 && value.size() != static_cast<std::size_t>(count))
        throw std::invalid_argument(key + " holds " + std::to_string(value.size()) + " entries where " +
                                    std::to_string(count) + " were expected");
    return value;
}

// binary_of's `count` values, each finite and in [low, high]; returns them.
template <class T>
std::vector<T> values_in(const nlohmann::json& value, const std::string& key, std::size_t count, double low,
                         double high) {
    std::vector<T> values;
    try {
        values = values_of<T>(value, count);
    } catch (const std::runtime_error& e) {
        throw std::invalid_argument(key + ": " + e.what());
    }
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double v = static_cast<double>(values[i]);
        if (!std::isfinite(v) || v < low || v > high)
            throw std::invalid_argument(key + "[" + std::to_string(i) + "] holds " + quoted(v) + ", outside " +
                                        range(low, high));
    }
    return values;
}

// One of `allowed`.
inline std::string one_of(const nlohmann::json& value, const std::string& key,
                          std::initializer_list<const char*> allowed) {
    std::string list;
    if (value.is_string())
        for (const char* a : allowed)
            if (value.get_ref<const std::string&>() == a) return a;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    throw std::invalid_argument(key + " is not one of " + list);
}

}  // namespace result_check

}  // namespace scenes
