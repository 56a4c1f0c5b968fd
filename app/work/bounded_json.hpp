#pragma once
// JSON and CBOR that someone else wrote (a work item's part, a parts
// manifest, a gallery folder's metadata), read so that no input can crash
// or exhaust figgen: the nesting is limited before anything recursive sees
// it (nlohmann's CBOR reader, copy and dump recurse once per level, so a
// few hundred thousand nested arrays overflow the stack), and a CBOR length
// header is checked against the bytes that follow it before anything is
// allocated for it.

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

namespace app {

// Deeper than anything figgen writes (a part is four levels deep).
inline constexpr int most_nesting = 64;

// Bad untrusted data: what() says what is wrong, in words that can follow
// "the part ... " or "the manifest ... ".
struct MalformedData : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// `bytes` as one CBOR data item of definite lengths, untagged, nested at
// most `max_depth` arrays and maps deep, with nothing after it.
// MalformedData otherwise, before any allocation a header asks for.
nlohmann::json cbor_bounded(std::string_view bytes, int max_depth = most_nesting);

// `text` as JSON nested at most `max_depth` arrays and objects deep;
// MalformedData otherwise (the parse stops at the first level too deep).
nlohmann::json json_bounded(std::string_view text, int max_depth = most_nesting);

}  // namespace app
