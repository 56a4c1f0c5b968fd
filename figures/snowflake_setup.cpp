#include "figures/snowflake_setup.hpp"

#include <algorithm>

#include "render/digest.hpp"
#include "sim/check.hpp"

namespace figures {
namespace {

const std::vector<Key> run_keys = {
    {"rule", "7-digit rule code d0..d6, d0 = 0"},
    {"label", "panel letter, e.g. \"(a)\""},
    {"restrict", "[first, last]: steps during which freezing is forbidden in the gaps between the arms"},
    {"priority", "steps during which growth is forced at the six tips"},
};

}  // namespace

std::vector<Key> snowflake_keys(std::vector<Key> extra) {
    std::vector<Key> keys = {
        {"runs", "list of runs, e.g. [{rule = \"0101010\", label = \"(a)\"}]"},
        {"rule", "rule code for every run, replacing the runs' own"},
        {"steps", "steps of every run, 0..100000"},
        {"restrict_radius", "restriction applies from this hex distance out, >= 1"},
        {"restrict_half_angle", "half-width in degrees of each forbidden wedge, (0, 30]"},
        {"priority_width", "cells beside each tip forced too, >= 0"},
        {"priority_exclusive",
         "true: during a priority step only the tips grow (the rule rests); false: they grow as well"},
    };
    keys.insert(keys.end(), extra.begin(), extra.end());
    return keys;
}

std::vector<SnowflakeRun> read_snowflake_runs(Settings& params, const std::string& id) {
    std::vector<SnowflakeRun> runs;
    try {
        const auto tables = params.tables("runs");
        const bool override_rule = params.has("rule");
        const std::string rule = params.text("rule", "0101010");
        const int restrict_radius = params.count("restrict_radius", 2);
        const double half_angle = params.number("restrict_half_angle", 15.0);
        const int priority_width = params.count("priority_width", 0);
        const bool priority_exclusive = params.flag("priority_exclusive", true);
        const std::size_t count = std::max<std::size_t>(tables.size(), 1);
        for (std::size_t i = 0; i < count; ++i) {
            Settings run("params.runs[" + std::to_string(i) + "]", i < tables.size() ? tables[i] : toml::table{},
                         run_keys);
            SnowflakeRun r;
            std::string letter = "(a)";
            letter[1] = static_cast<char>('a' + i % 26);
            r.label = run.text("label", letter);
            const std::string code = override_rule ? rule : run.text("rule", rule);
            r.params.rule = sim::SnowflakeRule::parse(code);
            const auto window = run.integers("restrict", {});
            if (!window.empty()) {
                if (window.size() != 2)
                    throw UsageError("params.runs[" + std::to_string(i) + "].restrict must be [first, last]");
                sim::require_integer("restrict first step", window[0], 1, 100000);
                sim::require_integer("restrict last step", window[1], window[0], 100000);
                r.params.restriction.first = static_cast<int>(window[0]);
                r.params.restriction.last = static_cast<int>(window[1]);
            }
            r.params.restriction.min_radius = restrict_radius;
            r.params.restriction.half_angle = half_angle;
            for (long long s : run.integers("priority", {})) {
                sim::require_integer("priority step", s, 1, 100000);
                r.params.priority.steps.push_back(static_cast<int>(s));
            }
            r.params.priority.width = priority_width;
            r.params.priority.exclusive = priority_exclusive;
            r.params.validate();
            r.used = run.used();
            r.used["rule"] = r.params.rule.code();
            runs.push_back(std::move(r));
        }
    } catch (const std::invalid_argument& e) {
        throw UsageError(id + ": " + e.what());
    }
    return runs;
}

nlohmann::json snowflake_settings(const sim::SnowflakeParams& p) {
    nlohmann::json meta = {{"rule", p.rule.code()}};
    if (p.restriction.last >= p.restriction.first)
        meta["restriction"] = {{"steps", {p.restriction.first, p.restriction.last}},
                               {"min_radius", p.restriction.min_radius},
                               {"half_angle_degrees", p.restriction.half_angle}};
    if (!p.priority.steps.empty())
        meta["priority"] = {
            {"steps", p.priority.steps}, {"width", p.priority.width}, {"exclusive", p.priority.exclusive}};
    return meta;
}

std::string snowflake_hash(const sim::Snowflake& crystal) {
    std::vector<sim::HexCell> cells = crystal.ice_cells();
    std::sort(cells.begin(), cells.end(), [](auto a, auto b) { return a.r != b.r ? a.r < b.r : a.q < b.q; });
    std::vector<std::int32_t> flat;
    for (auto c : cells) {
        flat.push_back(c.q);
        flat.push_back(c.r);
    }
    return render::sha256_hex(flat.data(), flat.size() * sizeof(std::int32_t));
}

}  // namespace figures
