// The README stays true: its grid shows every figure of the catalog, it
// stays a short front door whose links (and the docs' links) lead to files
// of the repository, and the descriptions docs/descriptions.md teaches with
// render.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "figgen_run.hpp"
#include "description/catalog.hpp"
#include "description/description.hpp"
#include "media/png_io.hpp"
#include "media/video.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path project = fs::path(FIGGEN_TEST_GOLDEN_DIR).parent_path().parent_path();

std::string text_of(const fs::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string readme() { return text_of(project / "README.md"); }

// The lines of a Markdown text outside its ``` fences.
std::vector<std::string> prose_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    bool fenced = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("```", 0) == 0) {
            fenced = !fenced;
            continue;
        }
        if (!fenced) lines.push_back(line);
    }
    return lines;
}

// The anchors of a Markdown file's headings, as GitHub makes them: lower
// case, spaces to hyphens, punctuation other than - and _ dropped.
std::set<std::string> anchors_of(const std::string& text) {
    std::set<std::string> anchors;
    for (const std::string& line : prose_lines(text)) {
        if (line.empty() || line[0] != '#') continue;
        const auto start = line.find_first_not_of('#');
        if (start == std::string::npos || line[start] != ' ') continue;
        std::string anchor;
        for (const char c : line.substr(start + 1)) {
            const auto u = static_cast<unsigned char>(c);
            if (c == ' ') anchor += '-';
            else if (std::isalnum(u) || c == '-' || c == '_' || u >= 0x80) anchor += char(std::tolower(u));
        }
        anchors.insert(anchor);
    }
    return anchors;
}

}  // namespace

TEST_CASE("the README's grid shows a committed thumbnail of every catalog figure, moving where it has a film", "[readme]") {
    const std::string text = readme();
    int shown = 0, moving = 0;
    for (const auto& file : description::catalog_files()) {
        const std::string id = file.stem().string();
        INFO(id);
        const bool film = description::load_description(file, {}).animation.has_value();
        // A figure with a film shows its preview's animated thumbnail.
        const std::string name = id + (film ? ".webp" : ".png");
        CHECK_THAT(text, Catch::Contains("](docs/thumbs/" + name + ")](figures/" + id + ".toml)"));
        const fs::path thumb = project / "docs" / "thumbs" / name;
        REQUIRE(fs::exists(thumb));
        if (film) {
            const media::PreviewInfo preview = media::probe_preview(thumb);
            CHECK(preview.width <= 240);
            CHECK(preview.height <= 180);
            CHECK(preview.frames > 1);
            CHECK(preview.loop_count == 0);
            ++moving;
        } else {
            const auto png = media::read_png(thumb).image;
            CHECK(png.width <= 240);
            CHECK(png.height <= 180);
        }
        ++shown;
    }
    // Counted again from the files themselves, with toml++: the grid misses none.
    int files = 0, films = 0;
    for (const auto& entry : fs::directory_iterator(project / "figures")) {
        if (entry.path().extension() != ".toml") continue;
        ++files;
        films += toml::parse_file(entry.path().string()).contains("animation");
    }
    CHECK(files > 30);
    CHECK(shown == files);
    CHECK(moving == films);
}

TEST_CASE("the README is a front door: short, licensed, its links and the docs' inside the repository",
          "[readme]") {
    const std::string text = readme();
    CHECK(std::count(text.begin(), text.end(), '\n') < 200);
    CHECK_THAT(text, Catch::Contains("](LICENSE)"));
    REQUIRE(fs::exists(project / "LICENSE"));
    // Every relative link of the README and of docs/*.md names a file of the
    // repository (a heading, where it names one), never one beside it.
    std::vector<fs::path> pages = {project / "README.md"};
    for (const auto& entry : fs::directory_iterator(project / "docs"))
        if (entry.path().extension() == ".md") pages.push_back(entry.path());
    CHECK(pages.size() > 5);
    static const std::regex link(R"(\]\(([^)\s]+)\))");
    int links = 0;
    for (const fs::path& page : pages) {
        const std::string markdown = text_of(page);
        for (const std::string& line : prose_lines(markdown)) {
            for (auto m = std::sregex_iterator(line.begin(), line.end(), link); m != std::sregex_iterator(); ++m) {
                const std::string target = (*m)[1];
                if (target.rfind("http://", 0) == 0 || target.rfind("https://", 0) == 0) continue;
                INFO(page.filename().string() << " links to " << target);
                ++links;
                const auto hash = target.find('#');
                const std::string file = target.substr(0, hash);
                const fs::path to = file.empty() ? page : (page.parent_path() / file).lexically_normal();
                const std::string inside = to.lexically_relative(project).string();
                CHECK(inside.rfind("..", 0) != 0);
                CHECK(fs::exists(to));
                if (hash != std::string::npos && fs::exists(to))
                    CHECK(anchors_of(text_of(to)).count(target.substr(hash + 1)) == 1);
            }
        }
    }
    CHECK(links > 50);
}

TEST_CASE("the descriptions docs/descriptions.md teaches with render", "[readme][cli]") {
    const std::string text = text_of(project / "docs" / "descriptions.md");
    // Every whole description in it (a ```toml block with a scene), rendered small.
    int rendered = 0;
    for (auto begin = text.find("```toml\n"); begin != std::string::npos; begin = text.find("```toml\n", begin + 8)) {
        const auto end = text.find("```", begin + 8);
        const std::string description = text.substr(begin + 8, end - begin - 8);
        if (description.find("\nscene ") == std::string::npos) continue;
        std::smatch id;
        REQUIRE(std::regex_search(description, id, std::regex(R"re((?:^|\n)id\s*=\s*"([^"]+)")re")));
        INFO(description);
        const fs::path dir = testkit::fresh_dir("docs-example-" + id[1].str());
        std::ofstream(dir / (id[1].str() + ".toml")) << description;
        const testkit::Run run = testkit::figgen("render " + (dir / (id[1].str() + ".toml")).string() +
                                                 " --format png --scale 0.3 --out " + (dir / "out").string());
        INFO(run.output);
        REQUIRE(run.status == 0);
        CHECK(fs::exists(dir / "out" / (id[1].str() + ".png")));
        CHECK(fs::exists(dir / "out" / (id[1].str() + ".json")));
        ++rendered;
    }
    CHECK(rendered >= 2);  // spots.toml and the Sierpinski L-systems
}

namespace {

// The targets `target` (a "dir/CMakeFiles/name.dir") depends on, directly
// or not, as CMake's generated build/CMakeFiles/Makefile2 lists them.
std::set<std::string> dependencies(const std::string& makefile2, const std::string& target) {
    std::map<std::string, std::vector<std::string>> direct;
    std::istringstream lines(makefile2);
    for (std::string line; std::getline(lines, line);) {
        const auto colon = line.find("/all: ");
        if (colon == std::string::npos || line.find(' ') < colon) continue;
        std::string to = line.substr(colon + 6);
        if (to.size() > 4 && to.compare(to.size() - 4, 4, "/all") == 0)
            direct[line.substr(0, colon)].push_back(to.substr(0, to.size() - 4));
    }
    std::set<std::string> all;
    std::vector<std::string> next = {target};
    while (!next.empty()) {
        const std::string t = next.back();
        next.pop_back();
        for (const std::string& d : direct[t])
            if (all.insert(d).second) next.push_back(d);
    }
    return all;
}

}  // namespace

TEST_CASE("make figures builds the program and its modules, not the tests", "[readme]") {
    // The Makefile's rule runs only CMake's figures target...
    const std::string makefile = testkit::slurp(std::filesystem::path(FIGGEN_SOURCE_DIR) / "Makefile");
    const auto rule = makefile.find("\nfigures:");
    REQUIRE(rule != std::string::npos);
    const std::string head = makefile.substr(rule + 1, makefile.find('\n', rule + 1) - rule - 1);
    INFO(head);
    CHECK(head.find(" build") == std::string::npos);  // not `make build` (everything) first
    const std::string recipe = makefile.substr(rule + 1, makefile.find("\n\n", rule + 1) - rule - 1);
    CHECK(recipe.find("--target figures") != std::string::npos);
    // ...which depends on figgen and the modules it opens, and on no test or benchmark.
    const std::string makefile2 = testkit::slurp(std::filesystem::path(FIGGEN_BUILD_DIR) / "CMakeFiles" / "Makefile2");
    if (makefile2.empty()) {
        WARN("no CMakeFiles/Makefile2: this build tree is not CMake's Unix Makefiles");
        return;
    }
    const std::set<std::string> needs = dependencies(makefile2, "figures/CMakeFiles/figures.dir");
    std::string listed;
    for (const std::string& n : needs) listed += n + " ";
    INFO("figures depends on: " << listed);
    CHECK(needs.count("app/CMakeFiles/figgen.dir") == 1);
    CHECK(needs.count("media/CMakeFiles/figgen_media.dir") == 1);
    CHECK(needs.count("render/vector/CMakeFiles/figgen_vector.dir") == 1);
    for (const std::string& n : needs) {
        CHECK(n.rfind("tests/", 0) != 0);
        CHECK(n.rfind("bench/", 0) != 0);
    }
}
