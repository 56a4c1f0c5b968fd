// Descriptions and options as someone else might share them: each runs in a
// sandbox whose whole tree (names, types, contents, link targets) is
// snapshotted before and after. Nothing outside the output folder may
// change, ever; on a refusal or a failure nothing inside changes either
// (not even the folder's creation); on success only the figure's own files.
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "child_process.hpp"
#include "figgen_run.hpp"
#include "base/digest.hpp"

namespace fs = std::filesystem;
using testkit::slurp;
using testkit::spill;

namespace {

// Every name under `root` with its type and contents, symlinks not followed.
std::map<std::string, std::string> tree(const fs::path& root) {
    std::map<std::string, std::string> found;
    if (!fs::exists(fs::symlink_status(root))) return found;
    for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
        const fs::file_status status = it->symlink_status();
        std::string what;
        if (fs::is_symlink(status)) {
            what = "link to " + fs::read_symlink(it->path()).string();
        } else if (fs::is_directory(status)) {
            what = "folder";
        } else if (fs::is_regular_file(status)) {
            const std::string bytes = slurp(it->path());
            what = "file " + base::sha256_hex(bytes.data(), bytes.size());
        } else {
            what = "other";
        }
        found[fs::relative(it->path(), root).string()] = what;
    }
    return found;
}

// The names in `after` that differ from `before` (added, removed or changed).
std::vector<std::string> changes(const std::map<std::string, std::string>& before,
                                 const std::map<std::string, std::string>& after) {
    std::vector<std::string> changed;
    for (const auto& [name, what] : after)
        if (!before.count(name) || before.at(name) != what) changed.push_back(name);
    for (const auto& [name, what] : before)
        if (!after.count(name)) changed.push_back(name);
    return changed;
}

// A small description of the diffusion scene: `top` gives its id line (or
// none), `animation` adds a short film.
std::string mine(const std::string& top, bool animation = false) {
    std::string text = top + "\nscene = \"diffusion\"\n[params]\nn = 12\n[figure]\npanels = [0, 3]\nsize = [96, 48]\n";
    if (animation) text += "[animation]\nsteps = [0, 4]\nsize = [48, 48]\n";
    return text;
}

// One sandbox: work/ is the working folder (with mine.toml, --out is
// work/out), outside/ holds what no run may touch.
struct Sandbox {
    fs::path root, work, out, outside;
    explicit Sandbox(const fs::path& at) : root(at), work(at / "work"), out(at / "work" / "out"), outside(at / "outside") {
        fs::create_directories(work);
        fs::create_directories(outside / "x-frames");
        spill(outside / "keep.txt", "keep me\n");
        spill(outside / "x-frames" / "00000.png", "not a png, but keep it\n");
        spill(work / "mine.toml", mine("id = \"mine\"", true));
        // An unprivileged child must be able to work here.
        for (const fs::path& p : {root, work, outside}) fs::permissions(p, fs::perms::all);
    }
    // figgen `args` run in work/; returns its exit status (-1: killed) and output.
    testkit::Run run(const std::vector<std::string>& args, const testkit::ChildOptions& options = {}) const {
        testkit::ChildOptions in_work = options;
        in_work.cwd = work;
        testkit::Child child(args, root / "log.txt", in_work);
        child.go();
        const int status = child.wait();
        testkit::Run result;
        result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        result.output = slurp(root / "log.txt");
        fs::remove(root / "log.txt");
        return result;
    }
};

struct Hostile {
    std::string what;
    std::vector<std::string> args;  // in work/
    int status;                     // 0, 1 (a write failed) or 2 (refused)
    std::string message;            // part of the one-line error
    std::function<void(const Sandbox&)> prepare = [](const Sandbox&) {};
    testkit::ChildOptions options = {};
};

const std::vector<std::string> render_mine = {"render", "mine.toml", "--out", "out", "--no-video"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

// A description file in work/ and the command rendering it.
Hostile description(const std::string& what, const std::string& text, int status, const std::string& message,
                    const std::string& file = "given.toml") {
    return {what, {"render", file, "--out", "out", "--no-video"}, status, message,
            [text, file](const Sandbox& s) { spill(s.work / file, text); }};
}

// Earlier outputs of mine.toml in out/ (PNG, JSON, MP4, frames).
void render_earlier(const Sandbox& s) {
    REQUIRE(s.run({"render", "mine.toml", "--out", "out", "--frames"}).status == 0);
    REQUIRE(fs::is_regular_file(s.out / "mine.json"));
}

// work/locked: a folder no one but root may write into.
void make_locked(const Sandbox& s) {
    fs::create_directory(s.work / "locked");
    fs::permissions(s.work / "locked", fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                           fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
}

std::vector<Hostile> hostile_cases() {
    const std::string id_rule = "is not allowed: a plain name of ASCII letters, digits";
    std::vector<Hostile> cases = {
        description("id with a parent part", mine("id = \"../x\""), 2, id_rule),
        description("id climbing two levels", mine("id = \"../../outside/keep\""), 2, id_rule),
        description("absolute id", mine("id = \"/tmp/figgen-hostile\""), 2, id_rule),
        description("id with a separator", mine("id = \"a/b\""), 2, id_rule),
        description("id with a backslash", mine("id = \"a\\\\b\""), 2, id_rule),
        description("id .", mine("id = \".\""), 2, id_rule),
        description("id ..", mine("id = \"..\""), 2, id_rule),
        description("id with .. inside", mine("id = \"a..b\""), 2, id_rule),
        description("empty id", mine("id = \"\""), 2, id_rule),
        description("hidden id", mine("id = \".mine\""), 2, id_rule),
        description("id with NUL", mine("id = \"a\\u0000b\""), 2, "\\x00"),
        description("id with a newline", mine("id = \"a\\nb\""), 2, "a\\nb"),
        description("id with a tab", mine("id = \"a\\tb\""), 2, id_rule),
        description("id with ESC (a terminal sequence)", mine("id = \"a\\u001b[2Jb\""), 2, "\\x1B"),
        description("id with a right-to-left override", mine("id = \"txt.\\u202Egnp\""), 2, "\\u202E"),
        description("id with a space", mine("id = \"my figure\""), 2, id_rule),
        description("id not ASCII", mine("id = \"\u00e9t\u00e9\""), 2, id_rule),
        description("id of 101 characters", mine("id = \"" + std::string(101, 'x') + "\""), 2, id_rule),
        description("id of 100 characters", mine("id = \"" + std::string(100, 'x') + "\""), 0, ""),
        description("id from a hidden file name", mine(""), 2, id_rule, ".hidden.toml"),
        description("id from a file name with a space", mine(""), 2, id_rule, "my figure.toml"),
        {"--set id with a parent part", with(render_mine, {"--set", "id=../outside/keep"}), 2, id_rule},
        {"--set id absolute", with(render_mine, {"--set", "id=/tmp/figgen-hostile"}), 2, id_rule},
        {"--set id with a newline", with(render_mine, {"--set", "id=a\nb"}), 2, "a\\nb"},
        {"--out is a file", {"render", "mine.toml", "--out", "../outside/keep.txt", "--no-video"}, 2,
         "cannot create the folder"},
        {"--out empty", {"render", "mine.toml", "--out", "", "--no-video"}, 2, "--out is empty"},
        {"--out inside a read-only folder", {"render", "mine.toml", "--out", "locked/out", "--no-video"}, 2,
         "--out locked/out: cannot create the folder",
         make_locked,
         testkit::ChildOptions::as_nobody()},
        {"--out a read-only folder", {"render", "mine.toml", "--out", "locked", "--no-video"}, 2,
         "--out locked: cannot write there",
         make_locked,
         testkit::ChildOptions::as_nobody()},
        description("a 17 MiB description", mine("id = \"big\"") + "# " + std::string(17 << 20, 'x') + "\n", 2,
                    "a description is at most 16 MiB"),
        {"/dev/zero as the description", {"render", "/dev/zero", "--out", "out"}, 2,
         "figure file /dev/zero is not allowed: a description is a regular .toml file"},
        {"--max-memory 0", with(render_mine, {"--max-memory", "0"}), 2, "--max-memory 0 is not allowed"},
        {"--max-disk negative", with(render_mine, {"--max-disk=-1"}), 2, "--max-disk -1 is not allowed"},
        {"duplicate panel steps", with(render_mine, {"--set", "figure.panels=[3,3]"}), 2, "each once"},
        description("a scene named by a path", "id = \"mine\"\nscene = \"../../x\"\n", 2, "scene"),
        // Things planted where outputs go: replaced, never written through.
        {"symlinks at the outputs", with(render_mine, {"--frames"}), 0, "",
         [](const Sandbox& s) {
             fs::create_directories(s.out);
             fs::create_symlink("../../outside/keep.txt", s.out / "mine.png");
             fs::create_symlink("../../outside/keep.txt", s.out / "mine.json");
             fs::create_symlink("../../outside/x-frames", s.out / "mine-frames");
         }},
        {"symlink at the film", {"render", "mine.toml", "--out", "out"}, 0, "",
         [](const Sandbox& s) {
             fs::create_directories(s.out);
             fs::create_symlink("../../outside/keep.txt", s.out / "mine.mp4");
         }},
        {"symlink at the lock", with(render_mine, {}), 0, "",
         [](const Sandbox& s) {
             fs::create_directories(s.out);
             fs::create_symlink("../../outside/keep.txt", s.out / ".mine~lock");
         }},
        // A folder or file where an output goes: the run fails naming it, and
        // none of its new files replace the earlier ones.
        {"a folder where the JSON goes", with(render_mine, {"--seed", "7"}), 1,
         "cannot write out/mine.json: a folder stands where the file goes",
         [](const Sandbox& s) {
             render_earlier(s);
             fs::remove(s.out / "mine.json");
             fs::create_directory(s.out / "mine.json");
         }},
        {"a folder where the PNG goes", {"render", "mine.toml", "--out", "out", "--frames", "--seed", "7"}, 1,
         "cannot write out/mine.png: a folder stands where the file goes",
         [](const Sandbox& s) {
             render_earlier(s);
             fs::remove(s.out / "mine.png");
             fs::create_directory(s.out / "mine.png");
             spill(s.out / "mine.png" / "inside.txt", "mine\n");
         }},
        {"a file where the frames go", {"render", "mine.toml", "--out", "out", "--frames", "--seed", "7"}, 1,
         "cannot write out/mine-frames: a file stands where the folder goes",
         [](const Sandbox& s) {
             render_earlier(s);
             fs::remove_all(s.out / "mine-frames");
             spill(s.out / "mine-frames", "a file\n");
         }},
        {"a full disk", {"render", "mine.toml", "--out", "out", "--seed", "7"}, 1, "File too large",
         render_earlier, testkit::ChildOptions::files_up_to(2048)},
        // The gallery reads only ID.* files of its folder.
        {"gallery with symlinked figures and a JSON naming files outside", {"gallery", "--out", "out"}, 0, "",
         [](const Sandbox& s) {
             fs::create_directories(s.out);
             spill(s.outside / "tc7-1.png", "outside\n");
             fs::create_symlink("../../outside/tc7-1.png", s.out / "tc7-1.png");
             spill(s.out / "tc7-1.json", "{\"id\": \"tc7-1\"}");
             REQUIRE(s.run({"render", "tc7-2", "--out", "out", "--set", "animation.steps=[0,40]"}).status == 0);
             spill(s.out / "tc7-2.json",
                   "{\"title\": 5, \"seed\": \"x\", \"animation\": {\"file\": \"../../outside/keep.txt\", "
                   "\"frames\": -3, \"size\": \"big\"}, \"image\": {\"file\": \"/etc/passwd\"}}");
         }},
    };
    return cases;
}

}  // namespace

TEST_CASE("hostile descriptions and options change nothing outside --out, and nothing at all when refused",
          "[cli][safety][hostile]") {
    const fs::path base = testkit::fresh_dir("hostile");
    int index = 0;
    for (const Hostile& c : hostile_cases()) {
        INFO(c.what);
        const Sandbox s(base / std::to_string(index++));
        c.prepare(s);
        const auto before = tree(s.root), outside_before = tree(s.outside);
        const testkit::Run run = s.run(c.args, c.options);
        INFO(run.output);
        CHECK(run.status == c.status);
        CHECK(tree(s.outside) == outside_before);
        const auto changed = changes(before, tree(s.root));
        if (c.status != 0) {
            CHECK(changed.empty());  // not even --out created
            CHECK_THAT(run.output, Catch::StartsWith("figgen: error: ") && Catch::Contains(c.message));
            CHECK(run.lines() == 1);
            CHECK(run.output.find("\xE2\x80\xAE") == std::string::npos);  // no raw bidirectional override
        } else {
            for (const std::string& name : changed) {
                INFO(name);
                CHECK((name == "work/out" || name.rfind("work/out/", 0) == 0));  // only in the output folder
                CHECK(name.find("~") == std::string::npos);  // no temporary or lock left
            }
        }
        if (c.args.front() == "gallery") {
            const std::string page = slurp(s.out / "index.html");
            CHECK(page.find("outside") == std::string::npos);
            CHECK(page.find("passwd") == std::string::npos);
            CHECK(page.find("id=\"tc7-1\"") == std::string::npos);  // its PNG is a symlink: not shown
            CHECK(page.find("id=\"tc7-2\"") != std::string::npos);
        }
    }
    CHECK(index >= 30);
}
