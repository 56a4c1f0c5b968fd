// Parts (app/work/schedule.hpp) as someone else may have left them: changed, forged
// with a matching hash, nested without end, lying in a length header, a
// FIFO where a file should be, a symlink where a folder should be. A merge
// refuses each with exit 2 and one line naming the folder, the item and
// what is wrong; a resume computes the item again, says so, and gives the
// bytes of one run. Nothing hangs and nothing crashes.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "figgen_run.hpp"
#include "base/digest.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using testkit::Run;
using testkit::slurp;
using testkit::spill;

namespace {

const std::string phase = "tc7-phase --no-video --scale 0.3 --set trials=10 --set walk_iterations=20 --threads 1";

// figgen `args`, killed if it runs past a minute (a hang fails, never stalls the suite).
Run figgen_bounded(const std::string& args) {
    return testkit::run_command(std::string("timeout -s KILL 60 ") + FIGGEN_EXE + " " + args);
}

// tc7-phase rendered in one go into plain/, and all its items as the one
// shard of one into shard/ (whose parts then stay). The two renders are made
// once a process, and each call gets its own copy: Catch2 runs a test case
// again from the top for each of its sections.
struct Sharded {
    fs::path dir, plain, shard, parts;
};
Sharded sharded(const std::string& name) {
    static const fs::path made = [] {
        const fs::path dir = testkit::fresh_dir("parts-made");
        REQUIRE(testkit::figgen("render " + phase + " --out " + (dir / "plain").string()).status == 0);
        const Run shard = testkit::figgen("render " + phase + " --shard 1/1 --out " + (dir / "shard").string());
        INFO(shard.output);
        REQUIRE(shard.status == 0);
        return dir;
    }();
    Sharded s;
    s.dir = testkit::fresh_dir(name);
    s.plain = s.dir / "plain";
    s.shard = s.dir / "shard";
    s.parts = s.shard / "tc7-phase.parts";
    fs::copy(made / "plain", s.plain, fs::copy_options::recursive);
    fs::copy(made / "shard", s.shard, fs::copy_options::recursive);
    REQUIRE(fs::exists(s.parts / "item-000000.cbor"));
    return s;
}

std::string sha256_of(const std::vector<std::uint8_t>& bytes) {
    return base::sha256_hex(bytes.data(), bytes.size());
}

std::string bytes_text(const std::vector<std::uint8_t>& bytes) { return std::string(bytes.begin(), bytes.end()); }

json read_part(const fs::path& file) {
    const std::string bytes = slurp(file);
    return json::from_cbor(bytes);
}

// The part with its result replaced by `result`; its hash made to match when `rehash`.
void write_result(const fs::path& file, const json& result, bool rehash) {
    json part = read_part(file);
    const std::vector<std::uint8_t> bytes = json::to_cbor(result);
    part["result"] = json::binary(bytes);
    if (rehash) part["result_sha256"] = sha256_of(bytes);
    spill(file, bytes_text(json::to_cbor(part)));
}

json result_of(const fs::path& file) { return json::from_cbor(read_part(file)["result"].get_binary()); }

// `depth` arrays, each holding the next, the last empty: 0x81 ... 0x80.
std::string nested_cbor(std::size_t depth) { return std::string(depth - 1, '\x81') + '\x80'; }

Run merge(const Sharded& s, const std::string& from) {
    return figgen_bounded("merge " + phase + " --from " + from + " --out " + (s.dir / "merged").string());
}

// A merge refused as it must be: exit 2, one line holding each of `expected`, nothing drawn.
void check_refused(const Sharded& s, const Run& run, const std::vector<std::string>& expected) {
    INFO(run.output);
    CHECK(run.status == 2);
    CHECK(run.lines() == 1);
    CHECK(run.output.size() < 1500);
    for (const std::string& e : expected) CHECK(run.output.find(e) != std::string::npos);
    CHECK_FALSE(fs::exists(s.dir / "merged"));  // refused before anything is created
}

}  // namespace

TEST_CASE("a merge refuses a part that is not as its shard wrote it, naming the folder and the item",
          "[cluster][parts]") {
    const Sharded s = sharded("parts-merge");
    const fs::path first = s.parts / "item-000000.cbor", walk = s.parts / "item-000021.cbor";
    const std::string named = (s.parts / "item-000000.cbor").string() + " (q = 0.5000)";
    SECTION("unchanged, the merge gives the bytes of one run") {
        const Run run = merge(s, s.shard.string());
        INFO(run.output);
        REQUIRE(run.status == 0);
        CHECK(slurp(s.dir / "merged" / "tc7-phase.png") == slurp(s.plain / "tc7-phase.png"));
        CHECK(slurp(s.dir / "merged" / "tc7-phase.json") == slurp(s.plain / "tc7-phase.json"));
    }
    SECTION("a result changed without its hash") {
        json r = result_of(first);
        r["percolating"] = r["percolating"].get<int>() == 0 ? 1 : 0;
        write_result(first, r, false);
        check_refused(s, merge(s, s.shard.string()),
                      {"figgen: error: --from: the part " + named, "does not match its SHA-256", "render that shard again"});
    }
    SECTION("a result forged with a matching hash, outside what its item can give") {
        write_result(first, {{"percolating", 11}}, true);  // 11 of 10 trials
        check_refused(s, merge(s, s.shard.string()),
                      {named, "has a result its item cannot give: percolating holds 11, outside [0, 10]"});
    }
    SECTION("NaN in the walk, with a matching hash") {
        REQUIRE(fs::exists(walk));
        json r = result_of(walk);
        r["walk"][3] = std::numeric_limits<double>::quiet_NaN();
        write_result(walk, r, true);
        check_refused(s, merge(s, s.shard.string()), {"item-000021.cbor (find_critical's walk)", "walk holds NaN"});
    }
    SECTION("an item index of 2^63") {
        json part = read_part(first);
        part["item"] = std::uint64_t{1} << 63;
        spill(first, bytes_text(json::to_cbor(part)));
        check_refused(s, merge(s, s.shard.string()), {named, "is not the part of item 0"});
    }
    SECTION("196,000 nested arrays: more bytes than the item's result takes") {
        spill(first, nested_cbor(196000));
        check_refused(s, merge(s, s.shard.string()), {named, "cannot be read or holds more than the"});
    }
    SECTION("60,000 nested arrays") {
        spill(first, nested_cbor(60000));
        check_refused(s, merge(s, s.shard.string()), {named, "nests arrays and maps more than 64 deep"});
    }
    SECTION("a result of 60,000 nested arrays, with a matching hash") {
        json part = read_part(first);
        const std::string deep = nested_cbor(60000);
        const std::vector<std::uint8_t> bytes(deep.begin(), deep.end());
        part["result"] = json::binary(bytes);
        part["result_sha256"] = sha256_of(bytes);
        spill(first, bytes_text(json::to_cbor(part)));
        check_refused(s, merge(s, s.shard.string()), {named, "has a result that nests arrays and maps more than 64 deep"});
    }
    SECTION("a length header claiming 2^60 entries") {
        spill(first, std::string("\x9b\x10\x00\x00\x00\x00\x00\x00\x00\x01", 10));
        check_refused(s, merge(s, s.shard.string()), {named, "claims a CBOR array of 1152921504606846976 entries"});
    }
    SECTION("a FIFO where a part should be: missing, not waited for") {
        fs::remove(first);
        REQUIRE(::mkfifo(first.c_str(), 0600) == 0);
        check_refused(s, merge(s, s.shard.string()), {"parts lack 1 of 22 items (q = 0.5000)"});
    }
    SECTION("a FIFO where the manifest should be") {
        fs::remove(s.parts / "manifest.json");
        REQUIRE(::mkfifo((s.parts / "manifest.json").c_str(), 0600) == 0);
        check_refused(s, merge(s, s.parts.string()), {"its parts manifest (manifest.json) is not a regular file"});
    }
    SECTION("a manifest nested a million deep") {
        spill(s.parts / "manifest.json", "{\"format\": " + std::string(1000000, '[') + "}");
        check_refused(s, merge(s, s.shard.string()), {"its parts manifest (manifest.json) nests arrays and objects more than 64 deep"});
    }
    SECTION("a manifest of 10 MB is not echoed") {
        json m = json::parse(slurp(s.parts / "manifest.json"));
        m["format"] = std::string(10 << 20, 'f');
        spill(s.parts / "manifest.json", m.dump());
        check_refused(s, merge(s, s.shard.string()), {"its parts are of another format", "bytes in all)"});
    }
    SECTION("a symlink where a --from folder's parts folder should be") {
        fs::create_directories(s.dir / "linked");
        fs::create_directory_symlink(s.parts, s.dir / "linked" / "tc7-phase.parts");
        check_refused(s, merge(s, (s.dir / "linked").string()), {"a symlink is not followed"});
    }
}

TEST_CASE("a resume computes a damaged part again, says so, and gives the bytes of one run", "[cluster][parts]") {
    const Sharded s = sharded("parts-resume");
    json r = result_of(s.parts / "item-000001.cbor");
    r["percolating"] = -3;
    write_result(s.parts / "item-000001.cbor", r, true);
    spill(s.parts / "item-000002.cbor", nested_cbor(60000));
    spill(s.parts / "item-000003.cbor", "");
    fs::remove(s.parts / "item-000004.cbor");
    REQUIRE(::mkfifo((s.parts / "item-000004.cbor").c_str(), 0600) == 0);
    const Run run = figgen_bounded("render " + phase + " --out " + s.shard.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK(run.output.find("item-000001.cbor (q = 0.5100) has a result its item cannot give: percolating holds -3, "
                          "outside [0, 10]; computing it again") != std::string::npos);
    CHECK(run.output.find("item-000002.cbor (q = 0.5200) nests arrays and maps more than 64 deep") != std::string::npos);
    CHECK(run.output.find("item-000003.cbor (q = 0.5300) ends inside a CBOR item") != std::string::npos);
    CHECK(run.output.find("resuming: 18 of 22 items kept") != std::string::npos);
    CHECK(slurp(s.shard / "tc7-phase.png") == slurp(s.plain / "tc7-phase.png"));
    CHECK(slurp(s.shard / "tc7-phase.json") == slurp(s.plain / "tc7-phase.json"));
    CHECK_FALSE(fs::exists(s.parts));
}
