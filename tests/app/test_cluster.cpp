// Work items beyond one process (app/work/schedule.hpp): MPI ranks, job-array shards
// and their merge, a resume after a kill. Each must give the very bytes of a
// plain single-process run: the PNG, and the JSON with every state hash.
#include <signal.h>
#include <sys/wait.h>
#include <toml++/toml.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "child_process.hpp"
#include "description/catalog.hpp"
#include "figgen_run.hpp"

namespace fs = std::filesystem;
using testkit::figgen;
using testkit::Run;
using testkit::run_command;
using testkit::slurp;

namespace {

// Whether a catalog description has a film.
bool t_has_animation(const fs::path& source) {
    return fs::exists(source) && toml::parse_file(source.string()).contains("animation");
}

// The figures with work items, made small: catalog descriptions with fewer
// or shorter runs, written into `dir`, and with `film` tc7-1 and the 1-D and
// 3-D formula figures, whose films are made in segments under mpirun (the
// 1-D film's frames hold the space-time diagram so far, the 3-D film ends
// turning round its last step). Returns their
// paths, space-separated.
std::string small_descriptions(const fs::path& dir, bool film = false) {
    struct Change {
        std::string id;
        std::vector<std::pair<std::string, toml::array>> arrays;
        std::vector<std::pair<std::string, std::int64_t>> integers;
    };
    const std::vector<Change> changes = {
        {"gs-atlas", {{"tiles", toml::array{5, 4}}}, {{"steps", 300}}},
        {"fx-pearson-map", {{"tiles", toml::array{3, 2}}}, {{"steps", 300}, {"width", 32}, {"height", 32}}},
        {"bd-roughness", {{"widths", toml::array{100, 200}}}, {{"seeds", 2}}},
        {"tc7-phase", {{"qs", toml::array{0.55, 0.65, 0.02}}}, {{"trials", 20}, {"walk_iterations", 30}}},
        {"tc7-ex1", {}, {{"n", 100}, {"gallery_steps", 15}}},
        {"tc7-1", {}, {}},
        {"pc-threshold", {{"sizes", toml::array{8, 16}}}, {{"samples", 400}, {"samples_per_item", 100}}},
        {"fx-tunnelling", {}, {{"steps", 1500}, {"width", 128}}},
        {"fx-glider-3d", {}, {{"steps", 150}, {"width", 16}, {"height", 16}, {"depth", 16}}},
    };
    std::string paths;
    for (const Change& c : changes) {
        const fs::path source = fs::path(FIGGEN_SOURCE_DIR) / "figures" / (c.id + ".toml");
        const bool filmed = c.id == "tc7-1" || (c.id.rfind("fx-", 0) == 0 && t_has_animation(source));
        if (!fs::exists(source) || (filmed && !film)) continue;  // not in this catalog, or not asked for
        toml::table t = toml::parse_file(source.string());
        toml::table& params = *t["params"].as_table();
        for (const auto& [key, value] : c.arrays) params.insert_or_assign(key, value);
        for (const auto& [key, value] : c.integers) params.insert_or_assign(key, value);
        // A film of 31 frames in segments of 8, so that 2 to 4 ranks share it.
        if (c.id == "tc7-1") {
            t["animation"].as_table()->insert_or_assign("steps", toml::array{0, 30});
            t["animation"].as_table()->insert_or_assign("segment_frames", 8);
        } else if (filmed) {
            const std::int64_t steps = params["steps"].value_or(std::int64_t{0});
            t["figure"].as_table()->insert_or_assign("panels", toml::array{0, steps});
            t["animation"].as_table()->insert_or_assign("steps", toml::array{0, steps});
            // 11 frames in segments of 4: three segments, a fourth with the turn.
            t["animation"].as_table()->insert_or_assign("stride", steps / 10);
            t["animation"].as_table()->insert_or_assign("segment_frames", 4);
            // The 3-D film ends turning round its last step: frames 11 to 14, in the segments' last two.
            if (c.id == "fx-glider-3d") t["animation"].as_table()->insert_or_assign("turn_frames", 4);
        }
        std::ofstream(dir / (c.id + ".toml")) << t << "\n";
        paths += ' ';  // appended apart: GCC 12 warns (-Wrestrict) on " " + string, wrongly
        paths += (dir / (c.id + ".toml")).string();
    }
    return paths;
}

std::vector<std::string> ids_in(const fs::path& dir) {
    std::vector<std::string> ids;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".toml") ids.push_back(entry.path().stem().string());
    return ids;
}

// Every figure of `ids` in `out` has the PNG and JSON bytes of `reference`,
// and no parts folder was left behind.
void check_same(const std::vector<std::string>& ids, const fs::path& reference, const fs::path& out) {
    for (const std::string& id : ids) {
        INFO(id << " in " << out);
        REQUIRE(fs::exists(out / (id + ".png")));
        CHECK(slurp(out / (id + ".png")) == slurp(reference / (id + ".png")));
        CHECK(slurp(out / (id + ".json")) == slurp(reference / (id + ".json")));
        if (fs::exists(reference / (id + ".mp4"))) CHECK(slurp(out / (id + ".mp4")) == slurp(reference / (id + ".mp4")));
    }
}

void check_no_parts(const std::vector<std::string>& ids, const fs::path& out) {
    for (const std::string& id : ids) CHECK_FALSE(fs::exists(out / (id + ".parts")));
}

// The work items' figures have no film; tc7-1's is made in segments.
const std::string small = " --scale 0.3";

#ifdef FIGGEN_TEST_MPI
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* sanitizer_options = "ASAN_OPTIONS=detect_leaks=0:intercept_tls_get_addr=0 ";
#else
constexpr const char* sanitizer_options = "";
#endif
// mpirun as root in a container, as CI runs: allowed as root, shared memory
// without the kernel's cross-memory attach (containers forbid it), and the
// in-node transports only.
// Under ASan (make test-sanitize) the ranks skip LeakSanitizer: Open MPI
// keeps what its components allocate past MPI_Finalize, and it has closed
// those components by then, so no suppression can name them; every other
// test keeps it.
std::string mpirun(int ranks) {
    return std::string(sanitizer_options) + "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
           "OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_btl=self,vader OMPI_MCA_pml=ob1 "
           "OMPI_MCA_mtl=^ofi OMPI_MCA_osc=^ucx mpirun --oversubscribe -n " +
           std::to_string(ranks) + " ";
}
#endif

}  // namespace

#ifdef FIGGEN_TEST_MPI
TEST_CASE("mpirun with 1 to 4 ranks gives the bytes of one process", "[cluster][mpi]") {
    const fs::path dir = testkit::fresh_dir("cluster-mpi");
    const std::string files = small_descriptions(dir, true);
    const std::vector<std::string> ids = ids_in(dir);
    const Run plain = figgen("render" + files + small + " --out " + (dir / "plain").string());
    INFO(plain.output);
    REQUIRE(plain.status == 0);
    // A plain run says nothing about ranks or parts: at most fx-tunnelling's
    // stability warning (forward Euler on Schroedinger's imaginary rates).
    std::istringstream said(plain.output);
    for (std::string line; std::getline(said, line);)
        CHECK(line.rfind("figgen: warning: fx-tunnelling: timestep", 0) == 0);
    // Dynamic schedules on 1..4 ranks, and the static one on 3.
    for (const std::string variant : {"1", "2", "3", "4", "3 static"}) {
        const int ranks = variant[0] - '0';
        const bool fixed = variant.size() > 1;
        const fs::path out = dir / ("ranks-" + std::to_string(ranks) + (fixed ? "-static" : ""));
        const Run run = run_command(mpirun(ranks) + FIGGEN_EXE + " render" + files + small +
                                    (fixed ? " --schedule static" : "") + " --out " + out.string());
        INFO(variant << ": " << run.output);
        REQUIRE(run.status == 0);
        check_same(ids, dir / "plain", out);
        check_no_parts(ids, out);
    }
}

#if !defined(__SANITIZE_ADDRESS__)  // ASan reserves terabytes of address space: no ulimit -v fits under it
TEST_CASE("a failing rank ends the mpirun with one line naming it and its item", "[cluster][mpi]") {
    // Rank 1 runs out of memory on the atlas's large tiles (its address space
    // limited to 300 MB: MPI_Init and the program with its text libraries
    // start in 230, a 2048 x 2048 tile does not fit); rank 0 says so and
    // ends the job; the tile rank 0 finished is kept.
    const fs::path out = testkit::fresh_dir("cluster-failing-rank");
    const auto start = std::chrono::steady_clock::now();
    const Run run =
        run_command(mpirun(2) + "sh -c '[ \"$OMPI_COMM_WORLD_RANK\" = 1 ] && ulimit -v 300000; exec " + FIGGEN_EXE +
                    " render gs-atlas --no-video --set n=2048 --set tiles=[2,2] --set "
                    "steps=20 --out " +
                    out.string() + "'");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    INFO(run.output);
    CHECK(run.status != 0);
    CHECK(seconds < 30);
    int error_lines = 0;
    std::istringstream lines(run.output);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("figgen: error:", 0) == 0) {
            ++error_lines;
            CHECK(line.find("figgen: error: rank 1: gs-atlas, tile ") == 0);
            CHECK(line.find("out of memory") != std::string::npos);
        }
    CHECK(error_lines == 1);
    CHECK_FALSE(fs::exists(out / "gs-atlas.png"));
    CHECK(fs::exists(out / "gs-atlas.parts" / "manifest.json"));
}
#endif

TEST_CASE("under mpirun a refused input is said once and nothing joins the job", "[cluster][mpi]") {
    const fs::path out = testkit::fresh_dir("cluster-refused");
    const Run run = run_command(mpirun(3) + FIGGEN_EXE + " render gs-atlas --set tiles=[0,5] --out " + out.string());
    INFO(run.output);
    CHECK(run.status == 2);
    std::size_t said = 0;
    for (std::size_t at = 0; (at = run.output.find("figgen: error:", at)) != std::string::npos; ++at) ++said;
    CHECK(said == 1);
    CHECK(run.output.find("tiles = 0 is not allowed") != std::string::npos);
    CHECK(fs::is_empty(out));
}
#endif

TEST_CASE("only a process an MPI launcher started opens MPI", "[cluster]") {
    const fs::path out = testkit::fresh_dir("cluster-no-mpi");
    const Run run =
        testkit::figgen_env("LD_DEBUG=files", "render tc7-phase --no-video --set trials=2 --out " + out.string());
    REQUIRE(run.status == 0);
    CHECK(run.output.find("libmpi") == std::string::npos);
    CHECK(run.output.find("libfiggen_mpi") == std::string::npos);
}

TEST_CASE("shards 1/3 2/3 3/3 and their merge give the bytes of one run", "[cluster]") {
    const fs::path dir = testkit::fresh_dir("cluster-shards");
    const std::string files = small_descriptions(dir);
    const std::vector<std::string> ids = ids_in(dir);
    REQUIRE(figgen("render" + files + small + " --out " + (dir / "plain").string()).status == 0);
    // Each shard in a folder of its own, as array tasks on separate scratch disks.
    std::string from;
    for (int k = 1; k <= 3; ++k) {
        const fs::path out = dir / ("shard-" + std::to_string(k));
        const Run shard =
            figgen("render" + files + small + " --shard " + std::to_string(k) + "/3 --out " + out.string());
        INFO(shard.output);
        REQUIRE(shard.status == 0);
        for (const std::string& id : ids) {
            CHECK_FALSE(fs::exists(out / (id + ".png")));  // a shard draws nothing
            CHECK(fs::exists(out / (id + ".parts") / "manifest.json"));
        }
        from += ' ';
        from += out.string();
    }
    SECTION("merged from every shard: the same bytes; the shards' parts stay") {
        const Run merge = figgen("merge" + files + small + " --from" + from + " --out " + (dir / "merged").string());
        INFO(merge.output);
        REQUIRE(merge.status == 0);
        check_same(ids, dir / "plain", dir / "merged");
        CHECK(fs::exists(dir / "shard-1" / "gs-atlas.parts" / "manifest.json"));
    }
    SECTION("a shard missing: refused, naming what is missing") {
        const Run merge = figgen("merge" + files + small + " --from " + (dir / "shard-1").string() + " " +
                                 (dir / "shard-3").string() + " --out " + (dir / "merged").string());
        INFO(merge.output);
        CHECK(merge.status == 2);
        CHECK(merge.lines() == 1);
        CHECK(merge.output.find("parts lack") != std::string::npos);
        CHECK_FALSE(fs::exists(dir / "merged" / "gs-atlas.png"));
    }
    SECTION("parts of other settings or another figgen: refused") {
        const Run seed =
            figgen("merge" + files + small + " --seed 5 --from" + from + " --out " + (dir / "merged").string());
        INFO(seed.output);
        CHECK(seed.status == 2);
        CHECK(seed.output.find("its parts are of another description, seed or --set") != std::string::npos);
        // A manifest from another version of figgen.
        const fs::path manifest = dir / "shard-2" / "gs-atlas.parts" / "manifest.json";
        nlohmann::json m = nlohmann::json::parse(slurp(manifest));
        m["figgen"] = "0.0.1";
        testkit::spill(manifest, m.dump());
        const Run version = figgen("merge" + files + small + " --from" + from + " --out " + (dir / "merged").string());
        INFO(version.output);
        CHECK(version.status == 2);
        CHECK(version.output.find("its parts are of another figgen version") != std::string::npos);
        CHECK_FALSE(fs::exists(dir / "merged" / "gs-atlas.png"));
    }
}

TEST_CASE("a killed run started again computes only what is missing and gives the bytes of one run", "[cluster]") {
    const fs::path dir = testkit::fresh_dir("cluster-resume");
    const std::string args = "gs-atlas --no-video --scale 0.3 --set tiles=[6,6] --set steps=3000 --threads 1";
    REQUIRE(figgen("render " + args + " --out " + (dir / "plain").string()).status == 0);
    const fs::path out = dir / "out", parts = out / "gs-atlas.parts";
    auto parts_done = [&] {
        int n = 0;
        std::error_code error;  // the folder goes when the run ends
        for (fs::directory_iterator e(parts, error), end; !error && e != end; e.increment(error))
            n += e->path().extension() == ".cbor";
        return n;
    };
    // Killed (SIGKILL: no clean-up at all) once 8 tiles are done. A test
    // starved of the CPU (ctest -j) may look too late, after the run ended:
    // then it tries again in a fresh folder.
    for (int attempt = 0; attempt < 3; ++attempt) {
        fs::remove_all(out);
        std::vector<std::string> argv = {"render"};  // Child runs figgen with these
        std::istringstream words(args + " --out " + out.string());
        for (std::string w; words >> w;) argv.push_back(w);
        testkit::Child child(argv, dir / "killed.log");
        child.go();
        for (int i = 0; i < 3000 && parts_done() < 8 && !fs::exists(out / "gs-atlas.png"); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        ::kill(child.pid(), SIGKILL);
        child.wait();
        if (parts_done() >= 8) break;
    }
    REQUIRE(fs::exists(parts));
    CHECK_FALSE(fs::exists(out / "gs-atlas.png"));
    int kept = 0;
    for (const auto& e : fs::directory_iterator(parts)) kept += e.path().extension() == ".cbor";
    REQUIRE(kept < 39);  // 36 tiles and 3 in double: killed before the end
    const Run again = figgen("render " + args + " --out " + out.string());
    INFO(again.output);
    REQUIRE(again.status == 0);
    CHECK(again.output.find("resuming: " + std::to_string(kept) + " of 39 items kept") != std::string::npos);
    check_same({"gs-atlas"}, dir / "plain", out);
    check_no_parts({"gs-atlas"}, out);
}

TEST_CASE("parts of other settings in the output folder are never used", "[cluster]") {
    const fs::path dir = testkit::fresh_dir("cluster-stale");
    const std::string args = "tc7-phase --no-video --scale 0.3 --set trials=10 --set walk_iterations=20";
    REQUIRE(figgen("render " + args + " --out " + (dir / "plain").string()).status == 0);
    // Half of the items under another seed, left in the folder.
    REQUIRE(figgen("render " + args + " --seed 9 --shard 1/2 --out " + (dir / "out").string()).status == 0);
    const Run run = figgen("render " + args + " --out " + (dir / "out").string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK(run.output.find("are of another description or figgen; computing anew") != std::string::npos);
    CHECK(run.output.find("resuming") == std::string::npos);
    check_same({"tc7-phase"}, dir / "plain", dir / "out");
}

TEST_CASE("shard and merge options are checked before anything runs", "[cluster]") {
    const fs::path out = testkit::fresh_dir("cluster-options");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"render tc7-phase --shard 4/3", "--shard 4/3 is not allowed: use K/N with 1 <= K <= N"},
        {"render tc7-phase --shard 0/3", "--shard 0/3 is not allowed"},
        {"render tc7-phase --shard 1/x", "--shard 1/x is not allowed"},
        {"render tc7-1 --shard 1/2", "--shard: tc7-1 has no work items to share; allowed: "},
        {"render tc7-phase --threads 0", "--threads: 0 is not allowed: use an integer from 1 to 1024"},
        // Integers are parsed into their range, never wrapped or trimmed.
        {"render tc7-phase --shard 1/4294967297", "--shard 1/4294967297 is not allowed"},
        {"render tc7-phase --shard 4294967297/2", "--shard 4294967297/2 is not allowed"},
        {"render tc7-phase '--shard= 1/2'", "--shard  1/2 is not allowed"},
        {"render tc7-phase --shard 1/2x", "--shard 1/2x is not allowed"},
        {"render tc7-phase --threads 4294967297", "--threads: 4294967297 is not allowed: use an integer from 1 to 1024"},
        {"render tc7-phase '--threads= 4'", "--threads:  4 is not allowed"},
        {"render tc7-phase --seed 18446744073709551617", "--seed: 18446744073709551617 is not allowed"},
        {"render tc7-phase --seed -1", "--seed: -1 is not allowed"},
        {"render tc7-phase --size 4294967396x450", "--size 4294967396x450 is not allowed: use WIDTHxHEIGHT"},
        {"render tc7-phase '--size= 100x450'", "--size  100x450 is not allowed"},
        {"render tc7-phase --size 100x450x", "--size 100x450x is not allowed"},
        {"render tc7-phase --schedule sometimes", "--schedule: sometimes not in {dynamic,static}"},
        {"merge tc7-phase --from " + (out / "nowhere").string(), "--from " + (out / "nowhere").string() + ": "},
        {"merge tc7-1 --from " + out.string(), "figgen merge: tc7-1 has no work items to share"},
    };
    for (const auto& [args, expected] : cases) {
        const Run run = figgen(args + " --out " + (out / "o").string());
        INFO(args << "\n" << run.output);
        CHECK(run.status == 2);
        CHECK(run.lines() == 1);
        CHECK(run.output.find(expected) != std::string::npos);
        CHECK_FALSE(fs::exists(out / "o"));
    }
}
