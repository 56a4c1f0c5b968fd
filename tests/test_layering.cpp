// The layering of the project's folders, read from their #include lines:
//   base/           files, digests, UTF-8, background work, modules: every layer may use it
//   sim/            the models: nothing of the project but sim/ (and base/)
//   render/         drawing's vocabulary, no GL: nothing but render/
//   render/gl/      the OpenGL canvas: render/
//   render/vector/  the PDF and SVG page: render/ (and render/gl/ for the pictures it embeds)
//   media/          PNG, films, thumbnails: render/ (images)
//   description/    the description reader: nothing but description/
//   ready/          Ready's files read: description, sim (a pattern read as a description of its rule)
//   ready/writers/  Ready's files written, an output: ready/ (the app uses it; scenes may not)
//   scenes/         sim, render (not render/gl/), description, ready (models meet drawing here)
//   app/command/    the command line and Python's library calls: everything
//   app/gallery/    the gallery: app/render/, app/work/ and everything below app/
//   app/render/     the render pipeline: app/work/ and everything below app/
//   app/work/       work items, parts, the schedule, MPI: everything below app/
// and no clock in sim/: a model's results never depend on time.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::map<std::string, std::set<std::string>> may_include = {
    {"base", {"base"}},
    {"sim", {"sim", "base"}},
    {"render", {"render", "base"}},
    {"render/gl", {"render/gl", "render", "base"}},
    {"render/vector", {"render/vector", "render/gl", "render", "base"}},
    {"media", {"media", "render", "base"}},
    {"description", {"description", "base"}},
    {"ready", {"ready", "description", "sim", "base"}},
    {"ready/writers", {"ready/writers", "ready", "base"}},
    // Scenes hand figures and frames as drawings: what owns a canvas and
    // reads it back is the command's (app/render/frame_canvas.hpp).
    {"scenes", {"sim", "render", "description", "ready", "scenes", "base"}},
    // The command, by role, each floor over the ones after it: the command
    // line and the library calls, the gallery, the render pipeline, the work.
    {"app", {}},
    {"app/command", {"sim", "render", "render/gl", "render/vector", "media", "description", "ready", "ready/writers",
                     "scenes", "base", "app/command", "app/gallery", "app/render", "app/work"}},
    {"app/gallery", {"sim", "render", "render/gl", "render/vector", "media", "description", "ready", "ready/writers",
                     "scenes", "base", "app/gallery", "app/render", "app/work"}},
    {"app/render", {"sim", "render", "render/gl", "render/vector", "media", "description", "ready", "ready/writers",
                    "scenes", "base", "app/render", "app/work"}},
    {"app/work", {"sim", "render", "render/gl", "render/vector", "media", "description", "ready", "ready/writers",
                  "scenes", "base", "app/work", "app/work/mpi"}},
    {"app/work/mpi", {"app/work/mpi", "base"}},
    // The Python module: figgen's library calls (app/command/) and what they hand over.
    {"python", {"app/command", "description", "ready", "scenes", "media", "base", "python"}},
};

// The layer a path (a file's, or an include's) belongs to: the longest
// folder of may_include it is in, or "" (a system header, a test's own).
std::string layer_of(const std::string& path) {
    std::string best;
    for (const auto& entry : may_include) {
        const std::string& folder = entry.first;
        if (path.compare(0, folder.size() + 1, folder + "/") == 0 && folder.size() > best.size()) best = folder;
    }
    return best;
}

// What a C++ file includes: the text inside "..." or <...> of each #include.
std::vector<std::string> includes_of(const fs::path& file) {
    static const std::regex include(R"(^\s*#\s*include\s*["<]([^">]+)[">])");
    std::vector<std::string> found;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_search(line, m, include)) found.push_back(m[1]);
    }
    return found;
}

// Every include under `root` that breaks the layering, as "file: includes X".
std::vector<std::string> layering_violations(const fs::path& root) {
    std::vector<std::string> violations;
    for (const auto& [folder, allowed] : may_include) {
        if (!fs::is_directory(root / folder)) continue;
        for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
            const std::string ext = entry.path().extension().string();
            if (ext != ".cpp" && ext != ".hpp" && ext != ".inc") continue;
            const std::string file = fs::relative(entry.path(), root).generic_string();
            if (layer_of(file) != folder) continue;  // a folder of its own (render/gl/ in render/)
            for (const std::string& included : includes_of(entry.path())) {
                const std::string layer = layer_of(included);
                const bool clock = folder == "sim" && (included == "chrono" || included == "ctime" ||
                                                       included == "sys/time.h" || included == "time.h");
                if ((!layer.empty() && !allowed.count(layer)) || clock)
                    violations.push_back(file + ": includes " + included);
            }
        }
    }
    return violations;
}

}  // namespace

TEST_CASE("every folder includes only the folders below it, and sim/ reads no clock", "[layering]") {
    const fs::path root = FIGGEN_SOURCE_DIR;
    for (const auto& [folder, allowed] : may_include) REQUIRE(fs::is_directory(root / folder));
    const auto violations = layering_violations(root);
    for (const auto& v : violations) UNSCOPED_INFO(v);
    CHECK(violations.empty());
}

TEST_CASE("the layering check finds an include that goes up and a clock in sim/", "[layering]") {
    const fs::path root = fs::temp_directory_path() / "figgen-layering-check";
    fs::remove_all(root);
    for (const char* folder : {"base", "sim", "render", "render/gl", "media", "description", "scenes", "app/command",
                               "app/render"})
        fs::create_directories(root / folder);
    std::ofstream(root / "scenes" / "fine.cpp") << "#include \"sim/model.hpp\"\n#include <vector>\n";
    std::ofstream(root / "app" / "command" / "main.cpp") << "#include \"scenes/scene.hpp\"\n";
    std::ofstream(root / "render" / "gl" / "canvas.cpp") << "#include \"render/surface.hpp\"\n#include \"base/digest.hpp\"\n";
    std::ofstream(root / "media" / "video.cpp") << "#include \"render/image.hpp\"\n";
    CHECK(layering_violations(root).empty());
    std::ofstream(root / "render" / "up.hpp") << "#pragma once\n  #  include \"sim/grid.hpp\"\n";
    std::ofstream(root / "render" / "plot.hpp") << "#include \"render/gl/canvas.hpp\"\n";
    std::ofstream(root / "base" / "up.cpp") << "#include \"render/image.hpp\"\n";
    std::ofstream(root / "scenes" / "up.cpp") << "#include \"app/render/output_files.hpp\"\n";
    std::ofstream(root / "sim" / "timed.cpp") << "#include <chrono>\n";
    std::ofstream(root / "description" / "up.cpp") << "#include \"scenes/scene.hpp\"\n";
    std::ofstream(root / "app" / "render" / "up.cpp") << "#include \"app/command/commands.hpp\"\n";
    auto violations = layering_violations(root);
    std::sort(violations.begin(), violations.end());
    CHECK(violations == std::vector<std::string>{"app/render/up.cpp: includes app/command/commands.hpp",
                                                 "base/up.cpp: includes render/image.hpp",
                                                 "description/up.cpp: includes scenes/scene.hpp",
                                                 "render/plot.hpp: includes render/gl/canvas.hpp",
                                                 "render/up.hpp: includes sim/grid.hpp",
                                                 "scenes/up.cpp: includes app/render/output_files.hpp",
                                                 "sim/timed.cpp: includes chrono"});
    fs::remove_all(root);
}
