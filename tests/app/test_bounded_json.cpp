// app/work/bounded_json.hpp: JSON and CBOR from someone else, read with their
// nesting and their length headers checked before anything recursive or
// anything large is done with them.
#include "app/work/bounded_json.hpp"

#include <catch2/catch.hpp>
#include <string>

using app::cbor_bounded;
using app::json_bounded;
using app::MalformedData;
using nlohmann::json;

namespace {

std::string cbor_text(const json& j) {
    const std::vector<std::uint8_t> bytes = json::to_cbor(j);
    return std::string(bytes.begin(), bytes.end());
}

// What cbor_bounded refuses `bytes` with ("" if it takes them).
std::string cbor_refusal(const std::string& bytes, int depth = app::most_nesting) {
    try {
        cbor_bounded(bytes, depth);
        return "";
    } catch (const MalformedData& e) {
        return e.what();
    }
}

std::string json_refusal(const std::string& text, int depth = app::most_nesting) {
    try {
        json_bounded(text, depth);
        return "";
    } catch (const MalformedData& e) {
        return e.what();
    }
}

}  // namespace

TEST_CASE("cbor_bounded reads back what figgen writes, every type and size of header", "[bounded_json]") {
    const json j = {{"item", 17},
                    {"negative", -70000},
                    {"big", std::uint64_t{1} << 40},
                    {"number", 0.1},
                    {"float", 0.5},
                    {"flags", {true, false, nullptr}},
                    {"name", std::string(300, 'x')},
                    {"bytes", json::binary(std::vector<std::uint8_t>(70000, 7))},
                    {"nested", {{{"a", {1, {2, {3}}}}}}},
                    {"empty", json::array()},
                    {"map", json::object()}};
    CHECK(cbor_bounded(cbor_text(j)) == j);
}

TEST_CASE("cbor_bounded refuses nesting past its limit without recursing", "[bounded_json]") {
    // 64 levels pass, 65 do not; 196,000 would overflow a recursive reader's stack.
    const auto nested = [](std::size_t depth) { return std::string(depth - 1, '\x81') + '\x80'; };
    CHECK(cbor_refusal(nested(64)).empty());
    CHECK(cbor_refusal(nested(65)) == "nests arrays and maps more than 64 deep (at byte 64)");
    CHECK(cbor_refusal(nested(196000)) == "nests arrays and maps more than 64 deep (at byte 64)");
    // Maps count as levels too: {"a": {"a": {}}} is three deep.
    const std::string maps = cbor_text({{"a", {{"a", json::object()}}}});
    CHECK(cbor_refusal(maps, 3).empty());
    CHECK(cbor_refusal(maps, 2) == "nests arrays and maps more than 2 deep (at byte 6)");
}

TEST_CASE("cbor_bounded refuses a length header beyond the bytes that follow, before allocating", "[bounded_json]") {
    // An array of 2^60 entries in ten bytes (nlohmann: "excessive array size").
    CHECK(cbor_refusal(std::string("\x9b\x10\x00\x00\x00\x00\x00\x00\x00\x01", 10)) ==
          "claims a CBOR array of 1152921504606846976 entries where 1 bytes follow (at byte 0)");
    // A byte string of 4 GiB, a text of 2 bytes with 1 there, a map of 3 pairs in 5 bytes.
    CHECK(cbor_refusal(std::string("\x5a\xff\xff\xff\xff\x00", 6)).find("claims a CBOR string of 4294967295 bytes") == 0);
    CHECK(cbor_refusal(std::string("\x62\x61", 2)).find("claims a CBOR string of 2 bytes where 1 follow") == 0);
    CHECK(cbor_refusal(std::string("\xa3\x61\x61\x01\x61", 5)).find("claims a CBOR map of 3 entries") == 0);
    // Cut short: in a header, in an array.
    CHECK(cbor_refusal(std::string("\x19\x01", 2)) == "ends inside a CBOR header (at byte 0)");
    CHECK(cbor_refusal(std::string("\x82\x82\x01\x01", 4)) == "ends inside a CBOR item (at byte 4)");
    CHECK(cbor_refusal("") == "ends inside a CBOR item (at byte 0)");
}

TEST_CASE("cbor_bounded refuses what figgen never writes, in words of its own", "[bounded_json]") {
    CHECK(cbor_refusal(std::string("\x9f\x01\xff", 3)).find("indefinite or reserved length") != std::string::npos);
    CHECK(cbor_refusal(std::string("\xc1\x01", 2)).find("holds a CBOR tag") == 0);
    CHECK(cbor_refusal(std::string("\xf7", 1)).find("holds a CBOR simple value") == 0);  // undefined
    CHECK(cbor_refusal(std::string("\x01\x02", 2)) == "has 1 bytes after its CBOR item");
    // A map whose key is a number: well-formed CBOR that nlohmann refuses; its words stay out.
    const std::string refused = cbor_refusal(std::string("\xa1\x01\x02", 3));
    CHECK(refused.find("does not decode as CBOR") == 0);
    CHECK(refused.find("json.exception") == std::string::npos);
}

TEST_CASE("json_bounded reads JSON nested up to its limit and refuses deeper, a million deep included",
          "[bounded_json]") {
    CHECK(json_bounded(R"({"a": [1, {"b": null}], "c": "d"})") == json::parse(R"({"a": [1, {"b": null}], "c": "d"})"));
    CHECK(json_refusal(std::string(64, '[') + std::string(64, ']')).empty());
    CHECK(json_refusal(std::string(65, '[') + std::string(65, ']')) == "nests arrays and objects more than 64 deep");
    CHECK(json_refusal("{\"format\": " + std::string(1000000, '[')) == "nests arrays and objects more than 64 deep");
    const std::string broken = json_refusal("{\"a\": tru}");
    CHECK(broken == "is not valid JSON (at byte 10)");
}
