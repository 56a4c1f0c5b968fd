#pragma once
// Numbers in a work item's result (scenes/work.hpp): arrays of floats or
// doubles as one CBOR byte string each, in the host's byte order (the ranks
// and shards of a run share a machine type), read back with their size
// checked, since a merge reads parts that came from elsewhere.

#include <cstdint>
#include <cstring>
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

}  // namespace scenes
