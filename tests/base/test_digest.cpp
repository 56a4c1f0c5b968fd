// SHA-256 (base/digest.hpp) against FIPS 180-2's examples: one run of
// bytes, and the same bytes given in pieces.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "base/digest.hpp"

TEST_CASE("SHA-256 gives FIPS 180-2's digests whole and in pieces", "[digest]") {
    const std::string abc = "abc";
    const std::string two = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
    const std::string abc_digest = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
    const std::string two_digest = "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1";
    CHECK(base::sha256_hex(abc.data(), abc.size()) == abc_digest);
    CHECK(base::sha256_hex(two.data(), two.size()) == two_digest);
    // The pieces laid end to end, cut anywhere (an empty piece too).
    for (std::size_t cut = 0; cut <= two.size(); cut += 7) {
        const std::vector<base::Bytes> pieces = {{two.data(), cut}, {two.data(), 0}, {two.data() + cut, two.size() - cut}};
        CHECK(base::sha256_hex(pieces) == two_digest);
    }
    const std::vector<base::Bytes> none;
    CHECK(base::sha256_hex(none) == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}
