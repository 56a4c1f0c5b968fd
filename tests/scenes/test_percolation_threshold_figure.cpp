// pc-threshold, the Newman-Ziff percolation threshold: its work items are
// blocks of samples drawn from their own streams, the figure is the same
// bits on one thread or two, and its estimate lands near Newman & Ziff's.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "description/catalog.hpp"
#include "description/description.hpp"
#include "figgen_run.hpp"
#include "media/png_io.hpp"
#include "scenes/scene.hpp"
#include "scenes/work_codec.hpp"
#include "sim/percolation_threshold.hpp"
#include "sim/random.hpp"

namespace fs = std::filesystem;

namespace {

constexpr double newman_ziff = 0.59274621;

// A small run: 3 sizes, 7 samples each in blocks of 3 (3 + 3 + 1).
const std::vector<std::string> small_run = {"sizes=[8,12,16]", "samples=7", "samples_per_item=3"};

// What a render through the command gives: its pixels and metadata.
struct Rendered {
    render::Image image;
    nlohmann::json meta;
};

Rendered read_rendered(const fs::path& out) {
    Rendered r;
    r.image = media::read_png(out / "pc-threshold.png").image;
    std::ifstream in(out / "pc-threshold.json");
    r.meta = nlohmann::json::parse(in);
    return r;
}

}  // namespace

TEST_CASE("pc-threshold work items hold the wrapping points of their own for_item streams", "[pc-threshold]") {
    const description::Description d =
        description::load_description(description::resolve_figure("pc-threshold"), small_run);
    const auto scene = scenes::read_scene(d, scenes::SceneOptions{});
    const scenes::WorkItems* items = scene->work();
    REQUIRE(items != nullptr);
    REQUIRE(items->item_count() == 9);
    const int sizes[] = {8, 12, 16};
    const int counts[] = {3, 3, 1};
    for (int item = 0; item < 9; ++item) {
        INFO("item " << item);
        const int size = sizes[item / 3], count = counts[item % 3], first = (item % 3) * 3;
        CHECK(items->item_name(item) == "L = " + std::to_string(size) + ", samples " + std::to_string(first) + " to " +
                                            std::to_string(first + count - 1));
        sim::Random rng = sim::Random::for_item(d.seed, static_cast<std::uint64_t>(item));
        const std::vector<sim::WrappingPoints> expected = sim::wrapping_points(size, count, rng);
        const nlohmann::json result = items->run_item(item);
        const auto h = scenes::values_of<std::uint32_t>(result.at("horizontal"), static_cast<std::size_t>(count));
        const auto v = scenes::values_of<std::uint32_t>(result.at("vertical"), static_cast<std::size_t>(count));
        for (int s = 0; s < count; ++s) {
            CHECK(h[s] == expected[s].horizontal);
            CHECK(v[s] == expected[s].vertical);
        }
        // The disk estimate holds: the stored CBOR is within item_bytes.
        CHECK(double(nlohmann::json::to_cbor(result).size()) <= items->item_bytes());
    }
    // The catalog's own blocks, at its largest L, within the bound as well.
    const description::Description full = description::load_description(description::resolve_figure("pc-threshold"));
    const auto catalog = scenes::read_scene(full, scenes::SceneOptions{});
    const scenes::WorkItems& all = *catalog->work();
    const int last = all.item_count() - 1;
    CHECK_THAT(all.item_name(last), Catch::StartsWith("L = 128, samples "));
    CHECK(double(nlohmann::json::to_cbor(all.run_item(last)).size()) <= all.item_bytes());
}

// Items run side by side on two threads: the L's samples are still its
// blocks' in item order. (MPI ranks and shards with a merge are checked for
// every figure with work items in tests/app/test_cluster.cpp.)
TEST_CASE("pc-threshold is the same bits on one thread or two", "[pc-threshold]") {
    const fs::path dir = testkit::fresh_dir("pc-threshold-threads");
    const std::string args =
        " pc-threshold --no-video --scale 0.4 --set sizes=[8,16,32] --set samples=200 "
        "--set samples_per_item=30 --out ";
    for (const char* threads : {"1", "2"}) {
        const testkit::Run run =
            testkit::figgen(std::string("render --threads ") + threads + args + (dir / threads).string());
        INFO(run.output);
        REQUIRE(run.status == 0);
    }
    const Rendered one = read_rendered(dir / "1"), two = read_rendered(dir / "2");
    CHECK(one.meta["work_items"]["count"] == 21);
    CHECK(two.image.rgba == one.image.rgba);
    CHECK(two.meta == one.meta);
    fs::remove_all(dir);
}

// A reduced figure: three sizes, 1,500 samples each (a fifth of the
// catalog's sampling time). The extrapolation's error bar is honest.
TEST_CASE("pc-threshold on a reduced run lands within 4 standard errors of 0.59274621", "[pc-threshold]") {
    const nlohmann::json meta =
        testkit::render_json("pc-threshold", "--set sizes=[16,32,64] --set samples=1500 --set samples_per_item=250");
    const nlohmann::json& fit = meta["extrapolation"];
    const double p_c = fit["p_c"], error = fit["standard_error"];
    INFO("p_c = " << p_c << " +- " << error);
    CHECK(error > 0);
    CHECK(error < 0.002);
    CHECK(std::abs(p_c - newman_ziff) < 4 * error);
    CHECK(meta["deviation_in_standard_errors"].get<double>() == Approx((p_c - newman_ziff) / error));
    REQUIRE(meta["estimates"].size() == 3);
    for (const auto& e : meta["estimates"]) {
        CHECK(e["samples"] == 1500);
        CHECK(std::abs(e["p_c"].get<double>() - newman_ziff) < 5 * e["standard_error"].get<double>());
    }
    REQUIRE(meta["crossings"].size() == 2);
    CHECK(meta["crossings"][0]["sizes"] == nlohmann::json({16, 32}));
    CHECK(meta["criterion"] == "one_direction");
    CHECK(meta["R_infinity_at_p_c"] == 0.521058290);
    CHECK(meta["state_sha256"].get<std::string>().size() == 64);
}
