#include "app/work/bounded_json.hpp"

#include <cstdint>
#include <vector>

namespace app {

namespace {

std::string at_byte(std::size_t byte) { return " (at byte " + std::to_string(byte) + ")"; }

// Walks the CBOR item in `bytes` without building it: one pass, a stack of
// the items each open array or map still holds, so its own depth costs no
// recursion. Refuses what figgen never writes (tags, indefinite lengths,
// simple values other than false, true and null).
void check_cbor(std::string_view bytes, int max_depth) {
    const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
    const std::size_t size = bytes.size();
    std::size_t pos = 0;
    std::vector<std::uint64_t> open;  // items left in each array or map not yet finished
    do {
        if (pos >= size) throw MalformedData("ends inside a CBOR item" + at_byte(pos));
        const std::size_t start = pos;
        const int major = data[pos] >> 5, info = data[pos] & 31;
        ++pos;
        std::uint64_t argument = 0;
        if (info < 24) {
            argument = static_cast<std::uint64_t>(info);
        } else if (info <= 27) {
            const std::size_t width = std::size_t{1} << (info - 24);
            if (size - pos < width) throw MalformedData("ends inside a CBOR header" + at_byte(start));
            for (std::size_t i = 0; i < width; ++i) argument = argument << 8 | data[pos + i];
            pos += width;
        } else {
            throw MalformedData("holds a CBOR header figgen never writes (indefinite or reserved length)" +
                                at_byte(start));
        }
        const std::uint64_t left = size - pos;
        switch (major) {
            case 0:
            case 1:
                break;
            case 2:
            case 3:
                if (argument > left)
                    throw MalformedData("claims a CBOR string of " + std::to_string(argument) + " bytes where " +
                                        std::to_string(left) + " follow" + at_byte(start));
                pos += static_cast<std::size_t>(argument);
                break;
            case 4:
            case 5: {
                // Each item takes at least one byte: a count beyond the bytes left is a lie.
                const std::uint64_t items = major == 5 ? (argument > left / 2 ? left + 1 : 2 * argument) : argument;
                if (items > left)
                    throw MalformedData("claims a CBOR " + std::string(major == 5 ? "map" : "array") + " of " +
                                        std::to_string(argument) + " entries where " + std::to_string(left) +
                                        " bytes follow" + at_byte(start));
                if (static_cast<int>(open.size()) >= max_depth)
                    throw MalformedData("nests arrays and maps more than " + std::to_string(max_depth) +
                                        " deep" + at_byte(start));
                if (items > 0) {
                    open.push_back(items);
                    continue;  // its items come next
                }
                break;
            }
            case 6:
                throw MalformedData("holds a CBOR tag, which figgen never writes" + at_byte(start));
            default:  // 7: simple values and floats
                if (!(info == 20 || info == 21 || info == 22 || info == 25 || info == 26 || info == 27))
                    throw MalformedData("holds a CBOR simple value figgen never writes" + at_byte(start));
                break;
        }
        // An item is finished: so is every container it was the last item of.
        while (!open.empty() && --open.back() == 0) open.pop_back();
    } while (!open.empty());
    if (pos != size) throw MalformedData("has " + std::to_string(size - pos) + " bytes after its CBOR item");
}

}  // namespace

nlohmann::json cbor_bounded(std::string_view bytes, int max_depth) {
    check_cbor(bytes, max_depth);
    try {
        return nlohmann::json::from_cbor(bytes.begin(), bytes.end(), true, true);
    } catch (const nlohmann::json::exception& e) {
        // The library's words name no file: the caller does, and says where.
        const auto* parse = dynamic_cast<const nlohmann::json::parse_error*>(&e);
        throw MalformedData("does not decode as CBOR" + (parse ? at_byte(parse->byte) : std::string()));
    }
}

nlohmann::json json_bounded(std::string_view text, int max_depth) {
    const nlohmann::json::parser_callback_t limit = [max_depth](int depth, nlohmann::json::parse_event_t event,
                                                                nlohmann::json&) {
        // `depth` counts the levels around the one that starts.
        if ((event == nlohmann::json::parse_event_t::object_start ||
             event == nlohmann::json::parse_event_t::array_start) &&
            depth >= max_depth)
            throw MalformedData("nests arrays and objects more than " + std::to_string(max_depth) + " deep");
        return true;
    };
    try {
        return nlohmann::json::parse(text.begin(), text.end(), limit, true, false);
    } catch (const nlohmann::json::parse_error& e) {
        throw MalformedData("is not valid JSON" + at_byte(e.byte));
    } catch (const nlohmann::json::exception&) {
        throw MalformedData("is not valid JSON");
    }
}

}  // namespace app
