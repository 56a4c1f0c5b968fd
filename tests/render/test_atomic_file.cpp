// Outputs made relative to an open folder: temporaries that are never a
// planted name, finals that replace a symlink instead of writing through it,
// and a commit group that puts all of its files in place or none.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "figgen_run.hpp"
#include "base/atomic_file.hpp"

namespace fs = std::filesystem;
using testkit::slurp;
using testkit::spill;

namespace {

// The names in `dir` that start with `prefix`.
std::vector<std::string> named(const fs::path& dir, const std::string& prefix) {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(prefix, 0) == 0) found.push_back(name);
    }
    return found;
}

}  // namespace

TEST_CASE("a temporary is never a name planted in advance", "[render][atomic]") {
    const fs::path dir = testkit::fresh_dir("atomic-planted");
    spill(dir / "secret.txt", "secret\n");
    const base::Folder folder(dir);
    // The first temporary shows the pattern: ".a.txt~tmp~PID~N".
    std::string first;
    {
        base::AtomicFile probe(folder, "a.txt");
        first = probe.temp_name();
    }
    const std::string pid = first.substr(first.find("~tmp~") + 5);    // "PID~N"
    const std::string pid_part = pid.substr(0, pid.find('~') + 1);       // "PID~"
    const unsigned long next = std::stoul(pid.substr(pid.find('~') + 1)) + 1;
    // Symlinks at the next ten names of "b.txt", and its final name, all to the secret.
    for (unsigned long n = next; n < next + 10; ++n)
        fs::create_symlink("secret.txt", dir / (".b.txt~tmp~" + pid_part + std::to_string(n)));
    fs::create_symlink("secret.txt", dir / "b.txt");
    base::write_file_atomically(folder, "b.txt", "new\n");
    CHECK(slurp(dir / "secret.txt") == "secret\n");
    CHECK(fs::is_regular_file(fs::symlink_status(dir / "b.txt")));  // the symlink replaced, not followed
    CHECK(slurp(dir / "b.txt") == "new\n");
    CHECK(named(dir, ".b.txt~tmp~").size() == 10);  // the planted ones skipped, still there, never opened
}

TEST_CASE("a commit group puts every file in place or none", "[render][atomic]") {
    const fs::path dir = testkit::fresh_dir("atomic-group");
    const base::Folder folder(dir);
    for (const char* name : {"x.png", "x.json", "x.mp4"}) spill(dir / name, std::string("old ") + name);

    SECTION("a rename that fails after others undoes them") {
        base::CommitGroup group;
        base::write_file_atomically(folder, "x.png", "new png");
        base::write_file_atomically(folder, "x.json", "new json");
        base::AtomicFile mp4(folder, "x.mp4");
        mp4.commit();
        fs::remove(dir / mp4.temp_name());  // the third cannot be moved in
        CHECK_THROWS_WITH(group.commit(), Catch::Contains((dir / "x.mp4").string()));
    }
    SECTION("a folder where a file goes fails before anything moves") {
        fs::remove(dir / "x.json");
        fs::create_directory(dir / "x.json");
        base::CommitGroup group;
        base::write_file_atomically(folder, "x.png", "new png");
        base::write_file_atomically(folder, "x.json", "new json");
        CHECK_THROWS_WITH(group.commit(), Catch::Contains((dir / "x.json").string()) &&
                                              Catch::Contains("a folder stands where the file goes"));
        CHECK(fs::is_directory(dir / "x.json"));  // as it was
        fs::remove(dir / "x.json");
        spill(dir / "x.json", "old x.json");  // for the checks below
    }
    CHECK(slurp(dir / "x.png") == "old x.png");
    CHECK(slurp(dir / "x.json") == "old x.json");
    CHECK(slurp(dir / "x.mp4") == "old x.mp4");
    CHECK(named(dir, ".").empty());  // no temporary, no earlier file left aside
}

TEST_CASE("a commit group replaces files, folders and symlinks together", "[render][atomic]") {
    const fs::path dir = testkit::fresh_dir("atomic-together");
    fs::create_directories(dir / "elsewhere");
    spill(dir / "elsewhere" / "kept.png", "kept");
    fs::create_symlink("elsewhere", dir / "x-frames");
    spill(dir / "x.png", "old");
    const base::Folder folder(dir);
    {
        base::CommitGroup group;
        base::AtomicDir frames(folder, "x-frames");
        base::write_file_atomically(frames.folder(), "00000.png", "frame");
        frames.commit();
        base::write_file_atomically(folder, "x.png", "new");
        CHECK(slurp(dir / "x.png") == "old");  // nothing in place before the group commits
        group.commit();
    }
    CHECK(slurp(dir / "x.png") == "new");
    CHECK(fs::is_directory(fs::symlink_status(dir / "x-frames")));
    CHECK(slurp(dir / "x-frames" / "00000.png") == "frame");
    CHECK(slurp(dir / "elsewhere" / "kept.png") == "kept");  // the symlink's target untouched
    CHECK(named(dir, ".").empty());
}

TEST_CASE("stale temporaries are removed by name, never another output's", "[render][atomic]") {
    const fs::path dir = testkit::fresh_dir("atomic-stale");
    fs::create_directories(dir / ".a.png~tmp~1~0");
    spill(dir / ".a.png~tmp~1~0" / "00000.png", "");
    spill(dir / ".a.json~old~2~5", "");
    spill(dir / ".a.png.png~tmp~3~0", "");  // figure "a.png"'s, not figure "a"'s
    spill(dir / "a.png", "output");
    const base::Folder folder(dir);
    CHECK(base::remove_stale_temporaries(folder, {"a.png", "a.json", "a.mp4", "a-frames"}) == 2);
    CHECK(named(dir, ".").size() == 1);
    CHECK(fs::exists(dir / ".a.png.png~tmp~3~0"));
    CHECK(slurp(dir / "a.png") == "output");
}
