#include "fuzz/fuzz_entries.hpp"

#include <stdexcept>
#include <string_view>

#include "description/description.hpp"
#include "scenes/scene.hpp"
#include "sim/lsystem.hpp"
#include "sim/snowflake.hpp"
#include "sim/turtle.hpp"

namespace fuzz {
namespace {

std::string_view text_of(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

std::vector<std::string> lines_of(std::string_view text) {
    std::vector<std::string> lines;
    while (!text.empty()) {
        const auto end = text.find('\n');
        lines.emplace_back(text.substr(0, end));
        if (end == std::string_view::npos) break;
        text.remove_prefix(end + 1);
    }
    return lines;
}

}  // namespace

Outcome description(const std::uint8_t* data, std::size_t size) {
    try {
        const description::Description d = description::parse_description(text_of(data, size), "fuzz.toml");
        (void)d.last_step(true);
        // The scene's phase 1: every setting read and checked, nothing run.
        description::at_source(d, [&] { return scenes::read_scene(d, scenes::SceneOptions{0.3, false}); });
        return Outcome::accepted;
    } catch (const description::UsageError&) {
        return Outcome::refused;
    }
}

Outcome set_assignments(const std::uint8_t* data, std::size_t size) {
    static const std::string base =
        "id = \"fuzz\"\nmodel = \"diffusion\"\n[params]\nn = 9\nr = 0.1\n[figure]\npanels = [0, 5]\n";
    try {
        const description::Description d = description::parse_description(base, "fuzz.toml", lines_of(text_of(data, size)));
        description::Settings params("params", d.params,
                                 {{"n", ""}, {"r", ""}, {"boundary", ""}, {"block_row", ""}, {"block_col", ""},
                                  {"block_size", ""}, {"block_value", ""}});
        (void)params.count("n", 9);
        (void)params.number("r", 0.1);
        (void)params.text("boundary", "zero");
        (void)params.integers("block_row", {});
        (void)params.numbers("block_value", {});
        (void)params.texts("block_col", {});
        (void)params.flag("block_size", false);
        return Outcome::accepted;
    } catch (const description::UsageError&) {
        return Outcome::refused;
    }
}

Outcome snowflake_rule(const std::uint8_t* data, std::size_t size) {
    sim::SnowflakeParams params;
    try {
        params.rule = sim::SnowflakeRule::parse(text_of(data, size));
    } catch (const std::invalid_argument&) {
        return Outcome::refused;
    }
    sim::Snowflake flake(params);
    for (int i = 0; i < 8; ++i) flake.step();
    (void)flake.ice_cells();
    return Outcome::accepted;
}

Outcome lsystem(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> lines = lines_of(text_of(data, size));
    const std::string axiom = lines.empty() ? std::string() : lines.front();
    if (!lines.empty()) lines.erase(lines.begin());
    sim::LSystem system;
    try {
        system = sim::LSystem::parse(axiom, lines);
    } catch (const std::invalid_argument&) {
        return Outcome::refused;
    }
    constexpr int depth = 4;
    for (const bool article : {false, true}) {
        if (sim::segment_count(system, depth, article) > 20'000) continue;
        sim::Turtle2Params turtle;
        turtle.segment_budget = 20'000;
        (void)sim::interpret_2d(system, depth, turtle, article);
    }
    if (sim::segment_count(system, depth, false) <= 20'000) {
        sim::Turtle3Params turtle;
        turtle.segment_budget = 20'000;
        (void)sim::interpret_3d(system, depth, turtle);
    }
    return Outcome::accepted;
}

const std::vector<Target>& targets() {
    static const std::vector<Target> all = {
        {"description", description},
        {"set", set_assignments},
        {"snowflake_rule", snowflake_rule},
        {"lsystem", lsystem},
    };
    return all;
}

}  // namespace fuzz
