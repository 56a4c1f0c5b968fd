// The fuzz targets' committed inputs replayed in the ordinary suite: every
// seed of tests/fuzz/corpus/<target>/ named ok-* must be accepted and every
// bad-* refused with the parser's own error; every input of
// tests/fuzz/regressions/<target>/ (an input that once crashed figgen or got
// past a check) must now return normally, and one named bad-* be refused.
// Under `make test-sanitize` this is ASan and UBSan clean.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "fuzz/fuzz_entries.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<std::uint8_t> bytes_of(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("the fuzz seeds are accepted or refused as named and the regressions run clean", "[fuzz]") {
    const fs::path root = FIGGEN_TEST_FUZZ_DIR;
    for (const fuzz::Target& target : fuzz::targets()) {
        INFO("target " << target.name);
        int seeds = 0, accepted = 0, refused = 0;
        for (const auto& entry : fs::directory_iterator(root / "corpus" / target.name)) {
            const std::string name = entry.path().filename().string();
            INFO(name);
            const auto input = bytes_of(entry.path());
            const fuzz::Outcome outcome = target.entry(input.data(), input.size());
            REQUIRE((name.rfind("ok-", 0) == 0 || name.rfind("bad-", 0) == 0));
            const bool ok = name.rfind("ok-", 0) == 0;
            CHECK(outcome == (ok ? fuzz::Outcome::accepted : fuzz::Outcome::refused));
            ++seeds;
            (ok ? accepted : refused) += 1;
        }
        CHECK(accepted >= 3);  // each target has valid seeds and refused ones
        CHECK(refused >= 3);
    }
}

TEST_CASE("the regressions of every fuzz target run clean", "[fuzz]") {
    // A missing folder fails: the loop below must not pass by finding nothing.
    const fs::path root = fs::path(FIGGEN_TEST_FUZZ_DIR) / "regressions";
    REQUIRE(fs::is_directory(root));
    int inputs = 0;
    for (const fuzz::Target& target : fuzz::targets()) {
        const fs::path regressions = root / target.name;
        if (!fs::exists(regressions)) continue;
        for (const auto& entry : fs::directory_iterator(regressions)) {
            const std::string name = entry.path().filename().string();
            INFO("regression " << target.name << "/" << name);
            const auto input = bytes_of(entry.path());
            fuzz::Outcome outcome = fuzz::Outcome::accepted;
            CHECK_NOTHROW(outcome = target.entry(input.data(), input.size()));
            if (name.rfind("bad-", 0) == 0) CHECK(outcome == fuzz::Outcome::refused);
            ++inputs;
        }
    }
    CHECK(inputs >= 2);
}
