// Nothing half-written: an interrupted render, a full disk and two renders
// into one folder each leave only whole files, and earlier outputs as they were.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "child_process.hpp"
#include "figgen_run.hpp"
#include "base/digest.hpp"
#include "media/png_io.hpp"

namespace fs = std::filesystem;
using testkit::Child;
using testkit::fresh_dir;
using testkit::slurp;

namespace {

// Every file under `dir` (recursively) with the SHA-256 of its bytes.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.is_regular_file()) {
            const std::string bytes = slurp(entry.path());
            files[fs::relative(entry.path(), dir).string()] = base::sha256_hex(bytes.data(), bytes.size());
        }
    return files;
}

// A temporary (".NAME~tmp~PID~N"), an earlier output moved aside
// (".NAME~old~PID~N") or a figure's lock (".ID~lock").
bool has_temporaries(const fs::path& dir) {
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name.find("~tmp~") != std::string::npos || name.find("~old~") != std::string::npos ||
            name.find("~lock") != std::string::npos)
            return true;
    }
    return false;
}

}  // namespace

TEST_CASE("SIGINT or SIGTERM during a render removes its temporaries and keeps earlier outputs", "[cli][safety]") {
    for (const int signal : {SIGINT, SIGTERM}) {
        INFO("signal " << signal);
        const fs::path out = fresh_dir("signal-" + std::to_string(signal));
        // Earlier outputs, with their PNG sequence.
        const testkit::Run first = testkit::figgen("render tc7-1 --frames --out " + out.string());
        REQUIRE(first.status == 0);
        const auto before = snapshot(out);
        REQUIRE(before.count("tc7-1.png") == 1);
        REQUIRE(before.count("tc7-1-frames/00000.png") == 1);

        // tc7-2 at twice the size with its film and frames takes seconds:
        // the signal comes as soon as its first temporary appears.
        Child child({"render", "tc7-2", "tc7-1", "--frames", "--seed", "5", "--scale", "2", "--out", out.string()},
                    out.parent_path() / ("signal-" + std::to_string(signal) + ".log"));
        child.go();
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (!has_temporaries(out) && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        REQUIRE(has_temporaries(out));
        std::this_thread::sleep_for(std::chrono::milliseconds(200));  // some frames written
        ::kill(child.pid(), signal);
        const int status = child.wait();
        REQUIRE(WIFEXITED(status));
        CHECK(WEXITSTATUS(status) == 128 + signal);  // 130, 143
        CHECK_FALSE(has_temporaries(out));
        CHECK(snapshot(out) == before);  // tc7-2 never finished; tc7-1 as it was
        CHECK_THAT(slurp(out.parent_path() / ("signal-" + std::to_string(signal) + ".log")),
                   Catch::Contains("stopped;") && Catch::Contains("unfinished output"));
    }
}

TEST_CASE("after a SIGKILL the next render into the folder removes what the killed one left", "[cli][safety]") {
    const fs::path out = fresh_dir("killed");
    REQUIRE(testkit::figgen("render tc7-1 --frames --out " + out.string()).status == 0);
    Child child({"render", "tc7-2", "--frames", "--scale", "2", "--out", out.string()},
                out.parent_path() / "killed.log");
    child.go();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!has_temporaries(out) && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the film, frames and lock under way
    ::kill(child.pid(), SIGKILL);
    const int status = child.wait();
    REQUIRE(WIFSIGNALED(status));
    REQUIRE(has_temporaries(out));  // nothing can clean up after SIGKILL
    const auto earlier = snapshot(out);

    // Another process, with another TMPDIR: the lock is in the output folder.
    Child again({"render", "tc7-2", "--frames", "--set", "animation.steps=[0,200]", "--out", out.string()},
                out.parent_path() / "killed-again.log",
                testkit::ChildOptions::with_environment({"TMPDIR=" + out.parent_path().string()}));
    again.go();
    const int second = again.wait();
    REQUIRE(WIFEXITED(second));
    CHECK(WEXITSTATUS(second) == 0);
    CHECK_FALSE(has_temporaries(out));
    const auto now = snapshot(out);
    for (const std::string name : {"tc7-1.png", "tc7-1.json", "tc7-1.mp4", "tc7-1-frames/00000.png"}) {
        INFO(name);
        CHECK(now.at(name) == earlier.at(name));  // the other figure's files untouched
    }
    CHECK(now.count("tc7-2.png") == 1);
    CHECK(now.count("tc7-2.mp4") == 1);
    CHECK(now.count("tc7-2-frames/00010.png") == 1);
    const auto meta = nlohmann::json::parse(slurp(out / "tc7-2.json"));
    CHECK(meta["animation"]["frames"] == 11);
}

TEST_CASE("a full disk gives a clear error and leaves no partial file", "[cli][safety]") {
    // The child may write files of at most `limit` bytes (RLIMIT_FSIZE, with
    // SIGXFSZ ignored): a write past it fails as on a full disk, with EFBIG
    // instead of ENOSPC. The film (57 KiB) is written first; without it, the
    // vector files asked for, then the PNG (7 KiB), then the JSON (3 KiB).
    struct Case {
        std::vector<std::string> options;
        rlim_t limit;
        std::string file;
    };
    // A PDF (7 KiB) and an SVG (15 KiB) are written before the PNG.
    // Each case's folder holds an earlier render of the figure, with its film.
    const fs::path earlier = fresh_dir("full-disk-earlier");
    REQUIRE(testkit::figgen("render tc7-1 --out " + earlier.string()).status == 0);
    for (const Case& c : {Case{{}, 4096, "tc7-1.mp4"}, Case{{"--no-video"}, 4096, "tc7-1.png"},
                          Case{{"--format", "pdf"}, 4096, "tc7-1.pdf"}, Case{{"--format", "svg"}, 4096, "tc7-1.svg"}}) {
        INFO(c.file);
        const fs::path out = fresh_dir("full-disk");
        fs::copy(earlier, out, fs::copy_options::recursive);
        const auto before = snapshot(out);
        REQUIRE(before == snapshot(earlier));
        const fs::path log = out.parent_path() / "full-disk.log";
        std::vector<std::string> args = {"render", "tc7-1", "--seed", "3", "--out", out.string()};
        args.insert(args.end(), c.options.begin(), c.options.end());
        Child child(args, log, testkit::ChildOptions::files_up_to(c.limit));
        child.go();
        const int status = child.wait();
        REQUIRE(WIFEXITED(status));
        CHECK(WEXITSTATUS(status) == 1);
        const std::string message = slurp(log);
        CHECK_THAT(message, Catch::StartsWith("figgen: error: cannot write ") && Catch::Contains(c.file) &&
                                Catch::Contains("File too large"));
        CHECK(std::count(message.begin(), message.end(), '\n') == 1);
        CHECK_FALSE(has_temporaries(out));
        CHECK(snapshot(out) == before);  // the earlier figure untouched, nothing half-new
    }
}

TEST_CASE("two figgen processes rendering into one folder leave whole, matching files", "[cli][safety]") {
    const fs::path out = fresh_dir("together");
    // What each would write alone.
    std::map<std::string, std::map<std::string, std::string>> alone;
    for (const std::string seed : {"1", "2"}) {
        const fs::path solo = fresh_dir("together-solo-" + seed);
        REQUIRE(testkit::figgen("render tc7-1 tc7-5 --frames --scale 0.5 --seed " + seed + " --out " + solo.string()).status == 0);
        alone[seed] = snapshot(solo);
    }

    // Each with a TMPDIR of its own: the lock they share is in the output folder.
    fs::create_directories(out.parent_path() / "tmp-a");
    fs::create_directories(out.parent_path() / "tmp-b");
    Child a({"render", "tc7-1", "tc7-5", "--frames", "--scale", "0.5", "--seed", "1", "--out", out.string()},
            out.parent_path() / "together-a.log",
            testkit::ChildOptions::with_environment({"TMPDIR=" + (out.parent_path() / "tmp-a").string()}));
    Child b({"render", "tc7-1", "tc7-5", "--frames", "--scale", "0.5", "--seed", "2", "--out", out.string()},
            out.parent_path() / "together-b.log",
            testkit::ChildOptions::with_environment({"TMPDIR=" + (out.parent_path() / "tmp-b").string()}));
    a.go();
    b.go();
    const int status_a = a.wait(), status_b = b.wait();
    REQUIRE(WIFEXITED(status_a));
    REQUIRE(WIFEXITED(status_b));
    CHECK(WEXITSTATUS(status_a) == 0);
    CHECK(WEXITSTATUS(status_b) == 0);
    CHECK_FALSE(has_temporaries(out));
    const auto together = snapshot(out);
    for (const std::string id : {"tc7-1", "tc7-5"}) {
        INFO(id);
        // Each figure's files all come from one of the two runs, whole: the
        // PNG's seed says which, and every file equals that run's alone.
        const auto png = media::read_png(out / (id + ".png"));
        std::string seed;
        for (const auto& [key, value] : png.text)
            if (key == "figgen:seed") seed = value;
        REQUIRE((seed == "1" || seed == "2"));
        auto of_figure = [&](const std::map<std::string, std::string>& files) {
            std::map<std::string, std::string> mine;
            for (const auto& [name, hash] : files)
                if (name.rfind(id + ".", 0) == 0 || name.rfind(id + "-frames/", 0) == 0) mine[name] = hash;
            return mine;
        };
        const auto written = of_figure(together), expected = of_figure(alone[seed]);
        CHECK(written.size() > 3);  // PNG, JSON, MP4 and the frames
        CHECK(written == expected);  // the same files, byte for byte (the seeds' films differ in length)
    }
}

#if !defined(__SANITIZE_ADDRESS__)  // ASan reserves terabytes of address space: no limit fits under it
TEST_CASE("memory running out is reported as memory, with the figure's estimate", "[cli][safety]") {
    // 8000^2 cells of doubles, five grids: about 2.4 GiB, in a process allowed 1.5 GiB.
    const fs::path out = fresh_dir("out-of-memory");
    const fs::path log = out.parent_path() / "out-of-memory.log";
    Child child({"render", "tc7-1", "--set", "n=8000", "--set", "figure.panels=[0,1]", "--no-video", "--max-memory",
                 "16G", "--out", out.string()},
                log, testkit::ChildOptions::memory_up_to(1500ull << 20));
    child.go();
    const int status = child.wait();
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 1);
    const std::string message = slurp(log);
    CHECK_THAT(message, Catch::StartsWith("figgen: error: tc7-1: out of memory (tc7-1, ") &&
                            Catch::Contains("its estimate was ") && Catch::Contains(" GiB"));
    CHECK(std::count(message.begin(), message.end(), '\n') == 1);
    CHECK(fs::is_empty(out));  // nothing written, no temporary left
}
#endif

TEST_CASE("a film is the same bytes on any number of threads, beside a CPU hog too", "[video][segments][cli]") {
    // 26 frames in segments of 4: seven segments, encoded one after another
    // (--threads 1) or side by side.
    const std::string film = "render tc7-2 --scale 0.5 --set 'animation.steps=[0,500]' --set animation.segment_frames=4";
    const auto run = [&](const std::string& threads, const std::string& name) {
        const fs::path out = testkit::fresh_dir("film-threads-" + name);
        const testkit::Run r = testkit::figgen(film + " --threads " + threads + " --out " + out.string());
        INFO(r.output);
        REQUIRE(r.status == 0);
        return testkit::slurp(out / "tc7-2.mp4");
    };
    const std::string expected = run("1", "1");
    REQUIRE(expected.size() > 1000);
    for (const std::string threads : {"2", "7"}) {
        INFO("--threads " << threads);
        CHECK(run(threads, threads) == expected);
    }
    // A busy loop on every core: the encoders finish in another order.
    const testkit::CpuHog hog(static_cast<int>(std::max(2u, std::thread::hardware_concurrency())));
    CHECK(run("7", "hog") == expected);
}
