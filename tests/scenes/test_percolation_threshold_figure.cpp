// pc-threshold, the Newman-Ziff percolation threshold: its work items are
// blocks of samples drawn from their own streams, and the figure is the
// same bits however they run (threads, shards and a merge, MPI ranks); its
// estimate lands near Newman & Ziff's.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "description/catalog.hpp"
#include "description/description.hpp"
#include "figgen_run.hpp"
#include "render/png_io.hpp"
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
    r.image = render::read_png(out / "pc-threshold.png").image;
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

TEST_CASE("pc-threshold is the same bits on one thread or two and from three shards merged", "[pc-threshold]") {
    const fs::path dir = testkit::fresh_dir("pc-threshold-split");
    std::string sets;
    for (const std::string& s :
         {std::string("sizes=[8,16,32]"), std::string("samples=200"), std::string("samples_per_item=30")})
        sets += " --set " + s;
    const std::string common = "pc-threshold --no-video --scale 0.4" + sets;
    // `after` follows the figure: merge's --from takes every word up to the next option.
    auto render = [&](const std::string& how, const fs::path& out, const std::string& after = "") {
        const testkit::Run run = testkit::figgen(how + " " + common + " --out " + out.string() + after);
        INFO(run.output);
        REQUIRE(run.status == 0);
    };
    render("render --threads 1", dir / "one");
    render("render --threads 2", dir / "two");
    std::string from;
    for (int k = 1; k <= 3; ++k) {
        render("render --shard " + std::to_string(k) + "/3", dir / ("shard" + std::to_string(k)));
        from += " --from " + (dir / ("shard" + std::to_string(k))).string();
    }
    render("merge", dir / "merged", from);
    const Rendered one = read_rendered(dir / "one");
    CHECK(one.meta["work_items"]["count"] == 21);
    for (const char* other : {"two", "merged"}) {
        INFO(other);
        const Rendered r = read_rendered(dir / other);
        CHECK(r.image.rgba == one.image.rgba);
        CHECK(r.meta == one.meta);
    }
    fs::remove_all(dir);
}

// Under mpirun when Open MPI is installed (figgen opens its MPI module only
// there): three ranks give the one-thread figure's bits.
TEST_CASE("pc-threshold over three MPI ranks is the same bits as on one thread", "[pc-threshold][mpi]") {
    if (testkit::run_command("command -v mpirun").status != 0) {
        WARN("no mpirun: not checked");
        return;
    }
    const fs::path dir = testkit::fresh_dir("pc-threshold-mpi");
    const std::string args = std::string(
        " pc-threshold --no-video --scale 0.4 --set sizes=[8,16] --set samples=120 "
        "--set samples_per_item=25 --out ");
    const testkit::Run alone = testkit::figgen("render --threads 1" + args + (dir / "alone").string());
    REQUIRE(alone.status == 0);
    const testkit::Run ranks = testkit::run_command(
        "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none "
        "mpirun --oversubscribe -n 3 " FIGGEN_EXE " render --threads 1" +
        args + (dir / "ranks").string());
    INFO(ranks.output);
    REQUIRE(ranks.status == 0);
    const Rendered a = read_rendered(dir / "alone"), b = read_rendered(dir / "ranks");
    CHECK(b.image.rgba == a.image.rgba);
    CHECK(b.meta == a.meta);
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
