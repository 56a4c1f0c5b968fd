// The layering of the project's folders, read from their #include lines:
//   sim/          the models: nothing of the project but sim/
//   render/       drawing: nothing of the project but render/
//   description/  the description reader: nothing but description/
//   scenes/       sim, render, description (models meet drawing here)
//   app/          the command: everything
// and no clock in sim/: a model's results never depend on time.
#include <catch2/catch.hpp>

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
    {"sim", {"sim"}},
    {"render", {"render"}},
    {"description", {"description"}},
    {"scenes", {"sim", "render", "description", "scenes"}},
    {"app", {"sim", "render", "description", "scenes", "app"}},
};

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
            if (ext != ".cpp" && ext != ".hpp") continue;
            for (const std::string& included : includes_of(entry.path())) {
                const auto slash = included.find('/');
                const std::string top = slash == std::string::npos ? "" : included.substr(0, slash);
                const bool ours = may_include.count(top) > 0;
                const bool clock = folder == "sim" && (included == "chrono" || included == "ctime" ||
                                                       included == "sys/time.h" || included == "time.h");
                if ((ours && !allowed.count(top)) || clock)
                    violations.push_back(fs::relative(entry.path(), root).string() + ": includes " + included);
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
    for (const char* folder : {"sim", "render", "description", "scenes", "app"}) fs::create_directories(root / folder);
    std::ofstream(root / "scenes" / "fine.cpp") << "#include \"sim/model.hpp\"\n#include <vector>\n";
    std::ofstream(root / "app" / "main.cpp") << "#include \"scenes/scene.hpp\"\n";
    CHECK(layering_violations(root).empty());
    std::ofstream(root / "render" / "up.hpp") << "#pragma once\n  #  include \"sim/grid.hpp\"\n";
    std::ofstream(root / "scenes" / "up.cpp") << "#include \"app/outputs.hpp\"\n";
    std::ofstream(root / "sim" / "timed.cpp") << "#include <chrono>\n";
    std::ofstream(root / "description" / "up.cpp") << "#include \"scenes/scene.hpp\"\n";
    const auto violations = layering_violations(root);
    CHECK(violations == std::vector<std::string>{"description/up.cpp: includes scenes/scene.hpp",
                                                 "render/up.hpp: includes sim/grid.hpp",
                                                 "scenes/up.cpp: includes app/outputs.hpp",
                                                 "sim/timed.cpp: includes chrono"});
    fs::remove_all(root);
}
