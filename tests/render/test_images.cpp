// Image-checksum tests: the test pattern and every figure description.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "description/catalog.hpp"
#include "golden_cases.hpp"
#include "image_check.hpp"

// Hidden from test discovery: tests/CMakeLists.txt registers one ctest per
// golden case ("golden image ID", run with -c ID), so `ctest -j` checks them
// side by side and a failure names its figure.
TEST_CASE("every golden image renders as recorded", "[.golden]") {
    // One section per case; tests/CMakeLists.txt runs each with -c NAME. A
    // name matching no case would enter no section and pass empty (Catch2
    // v2's --warn NoAssertions does not catch that), so that fails here.
    bool entered = false;
    for (const auto& c : testkit::golden_cases()) {
        SECTION(c.name) {
            entered = true;
            const auto check = testkit::check_golden(c.name, c.make());
            INFO(check.message);
            CHECK(check.within_tolerance);
        }
    }
    INFO("no section ran: -c names no golden case");
    CHECK(entered);
}

TEST_CASE("the golden cases are the three patterns and every catalog figure", "[golden]") {
    // tests/CMakeLists.txt lists the same names from figures/*.toml; a case
    // missing from that list would never be checked.
    std::set<std::string> expected = {"test-pattern", "plot-pattern", "tubes-pattern"};
    for (const auto& file : description::catalog_files()) expected.insert(file.stem().string());
    std::set<std::string> names;
    for (const auto& c : testkit::golden_cases()) names.insert(c.name);
    CHECK(names == expected);
}

TEST_CASE("the tolerant comparison catches a real change", "[golden]") {
    // Paint 1% of the test pattern's pixels: the hash must differ and the
    // tolerance (0.1%) must reject it, so the fallback is not a free pass.
    render::Image image = testkit::test_pattern();
    const int changed = image.width * image.height / 100;
    for (int i = 0; i < changed; ++i) {
        std::uint8_t* p = image.pixel(i % image.width, i / image.width);
        p[0] = static_cast<std::uint8_t>(p[0] ^ 0x80);
    }
    const auto check = testkit::check_golden("test-pattern", image);
    CHECK_FALSE(check.hash_matched);
    CHECK_FALSE(check.within_tolerance);
    CHECK(check.differing_pixels == changed);
}

TEST_CASE("the tolerant comparison accepts a small rendering difference", "[golden]") {
    render::Image image = testkit::test_pattern();
    image.pixel(10, 10)[1] = static_cast<std::uint8_t>(image.pixel(10, 10)[1] ^ 1);  // off by one in one channel
    const auto check = testkit::check_golden("test-pattern", image);
    CHECK_FALSE(check.hash_matched);
    CHECK(check.within_tolerance);
    CHECK(check.largest_delta == 1);
}
