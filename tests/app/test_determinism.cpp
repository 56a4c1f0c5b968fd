// Same bits every run: every figure of the catalog, rendered through the
// command three times at reduced size without video (on one thread, on one
// thread again, on two threads), gives the same decoded pixels, the same
// state hashes and the same metadata.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"
#include "description/catalog.hpp"
#include "golden_cases.hpp"
#include "render/png_io.hpp"

namespace {

struct Rendering {
    render::Image image;
    nlohmann::json meta;
};

// Renders figure `id` through the command into a fresh folder, with
// OMP_NUM_THREADS=threads in its environment, at the golden cases' reduced
// runs (testkit::golden_overrides) for the slow figures.
Rendering render_on_threads(const std::string& id, int threads, const std::string& run_name) {
    const std::filesystem::path out = testkit::fresh_dir("determinism-" + id + "-" + run_name);
    std::string args = "render " + id + " --no-video --scale 0.3 --out " + out.string();
    for (const auto& o : testkit::golden_overrides(id)) args.append(" --set '").append(o).append("'");
    const testkit::Run run = testkit::figgen_env("OMP_NUM_THREADS=" + std::to_string(threads), args);
    INFO(run.output);
    REQUIRE(run.status == 0);
    Rendering r;
    r.image = render::read_png(out / (id + ".png")).image;
    std::ifstream in(out / (id + ".json"));
    r.meta = nlohmann::json::parse(in);
    std::filesystem::remove_all(out);
    return r;
}

// Every "state_sha256" in the metadata, as "where = hash", in document order.
void collect_hashes(const nlohmann::json& j, const std::string& where, std::vector<std::string>& hashes) {
    if (j.is_object()) {
        for (const auto& [key, value] : j.items()) {
            if (key == "state_sha256")
                hashes.push_back(where + "/" + key + " = " + value.get<std::string>());
            else
                collect_hashes(value, where + "/" + key, hashes);
        }
    } else if (j.is_array()) {
        for (std::size_t i = 0; i < j.size(); ++i) collect_hashes(j[i], where + "/" + std::to_string(i), hashes);
    }
}

std::vector<std::string> hashes_of(const nlohmann::json& meta) {
    std::vector<std::string> hashes;
    collect_hashes(meta, "", hashes);
    return hashes;
}

// Pixels whose RGBA differ anywhere; every pixel when the sizes differ.
long differing_pixels(const render::Image& a, const render::Image& b) {
    if (a.width != b.width || a.height != b.height) return std::max(1L, long(a.width) * a.height);
    long differ = 0;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4) differ += !std::equal(&a.rgba[i], &a.rgba[i] + 4, &b.rgba[i]);
    return differ;
}

void check_same(const Rendering& reference, const Rendering& other, const std::string& what) {
    INFO(what);
    CHECK(other.image.width == reference.image.width);
    CHECK(other.image.height == reference.image.height);
    CHECK(differing_pixels(reference.image, other.image) == 0);
    CHECK(hashes_of(other.meta) == hashes_of(reference.meta));
    // The whole metadata: it holds no timing, path or thread count, so
    // nothing in it may legitimately differ between runs.
    const nlohmann::json patch = nlohmann::json::diff(reference.meta, other.meta);
    INFO("metadata differences (JSON patch from the first run): " << patch.dump());
    CHECK(patch.empty());
}

std::set<std::string> catalog_ids() {
    std::set<std::string> ids;
    for (const auto& file : description::catalog_files()) ids.insert(file.stem().string());
    return ids;
}

}  // namespace

// Hidden from test discovery: tests/CMakeLists.txt registers one ctest per
// catalog figure ("determinism ID", run with -c ID), so `ctest -j` runs them
// side by side and a failure names its figure.
TEST_CASE("every figure renders the same bits every run", "[.determinism]") {
    // Each run of the test case enters one section; with -c naming no
    // catalog id it would enter none and pass empty (Catch2 v2's
    // --warn NoAssertions does not catch that), so that fails here.
    bool entered = false;
    for (const auto& file : description::catalog_files()) {
        const std::string id = file.stem().string();
        SECTION(id) {
            entered = true;
            const Rendering first = render_on_threads(id, 1, "1a");
            const Rendering again = render_on_threads(id, 1, "1b");
            const Rendering two = render_on_threads(id, 2, "2");
            {
                // The state hashes are what tells a changed model from a
                // changed drawing: every figure must have at least one.
                INFO(id << " has no state_sha256 in its metadata");
                REQUIRE_FALSE(hashes_of(first.meta).empty());
            }
            check_same(first, again, id + ": one thread, twice");
            check_same(first, two, id + ": one thread against two");
        }
    }
    INFO("no section ran: -c names no figure of the catalog " << description::catalog_dir().string());
    CHECK(entered);
}

TEST_CASE("the determinism tests are one per catalog figure", "[determinism]") {
    // tests/CMakeLists.txt registers "determinism ID" for the ids it globbed
    // from figures/*.toml (FIGGEN_DETERMINISM_IDS); the sections above run
    // over the catalog. A figure missing from either is never checked.
    std::set<std::string> registered;
    std::stringstream list(FIGGEN_DETERMINISM_IDS);
    for (std::string id; std::getline(list, id, ',');) registered.insert(id);
    CHECK(registered == catalog_ids());
    CHECK(!registered.empty());
}
