// Every key a catalog figure's scene allows is read and checked for that
// figure: a value outside what the key allows is refused with a
// SettingError naming the key, before anything runs (figgen exits 2). A key
// that a scene reads only for some drawings would take anything where it is
// not read (tc7-ex2's style.colormap beside its colours was ignored in
// silence): this walk finds such keys.
#include <toml++/toml.h>

#include <catch2/catch.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "description/catalog.hpp"
#include "description/description.hpp"
#include "description/settings.hpp"
#include "figgen_run.hpp"
#include "scenes/scene.hpp"

using description::Description;
using description::SettingsLog;

namespace {

struct Section {
    std::string name;
    std::vector<std::string> keys;
};

// The sections and keys `file`'s description and its scene allow, as `figgen describe` lists them.
std::vector<Section> keys_of(const std::filesystem::path& file) {
    SettingsLog log;
    const Description d = description::load_description(file);
    scenes::read_scene(d, scenes::SceneOptions{0.3, false});
    std::vector<Section> sections;
    for (const auto& s : log.sections) {
        Section section{s.name, {}};
        for (const description::Key& k : s.keys) section.keys.push_back(k.name);
        sections.push_back(section);
    }
    return sections;
}

// `file`'s description with `key` of `section` ("": the top level) set to
// `value` (TOML), written out again.
std::optional<std::string> with_value(const std::filesystem::path& file, const std::string& section, const std::string& key,
                       const std::string& value) {
    toml::table root = toml::parse_file(file.string());
    toml::table holder = toml::parse("v = " + value);
    // "params.plants[1]": a section, a list in it, a table of the list.
    toml::table* into = &root;
    std::istringstream path(section);
    for (std::string part; std::getline(path, part, '.');) {
        const auto bracket = part.find('[');
        const std::string name = part.substr(0, bracket);
        if (!into->contains(name)) into->insert(name, toml::table{});
        toml::node* node = into->get(name);
        if (bracket != std::string::npos)
            node = node->is_array() ? node->as_array()->get(std::stoul(part.substr(bracket + 1))) : nullptr;
        // A plant of [params] alone ("plants[0]" where the file lists none) has no table to write into.
        if (!node || !node->is_table()) return std::nullopt;
        into = node->as_table();
    }
    into->insert_or_assign(key, std::move(*holder.get("v")));
    std::ostringstream text;
    text << root;
    return text.str();
}

}  // namespace

TEST_CASE("every key of every catalog figure refuses a value outside what it allows, naming the key",
          "[keys][describe]") {
    // Values no key allows all of: NaN (no number, list or string key takes
    // it), a string that names nothing, a number beyond every range, a list of lists.
    const std::vector<std::string> outside = {"nan", "\"nan\"", "-1e300", "[[]]"};
    int walked = 0;
    std::set<std::string> scenes_seen;
    // The catalog: it has a figure of every scene (checked below).
    const std::vector<std::filesystem::path> files = description::catalog_files();
    for (const std::filesystem::path& file : files) {
        const std::string id = file.stem().string();
        scenes_seen.insert(description::load_description(file).scene);
        for (const Section& section : keys_of(file)) {
            for (const std::string& key : section.keys) {
                // [params] keys and the top-level ones are written bare in messages.
                const bool top = section.name == "description";
                if (top && (key == "params" || key == "style" || key == "figure" || key == "animation")) continue;
                const std::string written = description::as_written(top ? key : section.name + "." + key);
                std::string tried;
                bool refused = false;
                if (!with_value(file, top ? "" : section.name, key, "0")) continue;
                for (const std::string& value : outside) {
                    try {
                        const Description d =
                            description::parse_description(*with_value(file, top ? "" : section.name, key, value), file);
                        description::at_source(d, [&] { return scenes::read_scene(d, scenes::SceneOptions{0.3, false}); });
                        tried += value + ": accepted; ";
                    } catch (const description::UsageError& e) {
                        // "<where>: key = value is not allowed: ..." or "<where>: key[2] = ...".
                        const std::string message = e.what();
                        if (message.find(": " + written + " = ") != std::string::npos ||
                            message.find(": " + written + "[") != std::string::npos) {
                            refused = true;
                            break;
                        }
                        tried += value + ": refused without naming it (" + message + "); ";
                    }
                }
                INFO(id << ": " << written << " = ...: " << tried);
                CHECK(refused);
                ++walked;
            }
        }
    }
    // Every scene was walked, through the keys of its figures.
    CHECK(scenes_seen.size() == scenes::all_scenes().size());
    CHECK(walked > 400);
}

TEST_CASE("a colormap given beside colours is refused, not ignored", "[keys]") {
    const std::filesystem::path out = testkit::fresh_dir("keys-colormap");
    for (const std::string value : {"nope", "viridis"}) {
        const testkit::Run run =
            testkit::figgen("render tc7-ex2 --no-video --set style.colormap=" + value + " --out " + out.string());
        INFO(run.output);
        CHECK(run.status == 2);
        CHECK(run.lines() == 1);
        CHECK(run.output.find("style.colormap = ") != std::string::npos);
        CHECK(run.output.find(value == "nope" ? "one of Reds, Blues"
                                             : "give one of the two (--cmap replaces colours)") != std::string::npos);
    }
    CHECK_FALSE(std::filesystem::exists(out / "tc7-ex2.png"));
}
