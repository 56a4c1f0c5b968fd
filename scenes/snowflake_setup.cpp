#include "scenes/snowflake_setup.hpp"

#include <algorithm>

#include "scenes/model_check.hpp"
#include "base/digest.hpp"

namespace scenes {
namespace {

const std::vector<Key> run_keys = {
    {"rule", "7-digit rule code d0..d6, d0 = 0"},
    {"label", "panel letter, e.g. \"(a)\""},
    {"restrict", "[first, last]: steps during which freezing is forbidden in the gaps between the arms"},
    {"priority", "steps during which growth is forced at the six tips"},
};

// The keys every run shares (the rule, the restriction's region, the
// priority's width), checked by the model on a run made of them alone: a
// mistake there names the [params] key, not each run.
sim::SnowflakeParams read_shared(Settings& params) {
    sim::SnowflakeParams p;
    const std::string rule = params.text("rule", "0101010");
    check_model(params, [&] { p.rule = sim::SnowflakeRule::parse(rule); });
    p.restriction.min_radius = params.count("restrict_radius", 2);
    p.restriction.half_angle = params.number("restrict_half_angle", 15.0);
    p.priority.width = params.count("priority_width", 0);
    p.priority.exclusive = params.flag("priority_exclusive", true);
    check_model(params, [&] { p.validate(); },
                {{"restriction.min_radius", "restrict_radius"},
                 {"restriction.half_angle", "restrict_half_angle"},
                 {"priority.width", "priority_width"}});
    return p;
}

// A run's restrict = [first, last]: absent, no restriction.
void read_restriction_window(Settings& run, sim::Restriction& restriction) {
    const auto window = run.integers("restrict", {});
    if (window.empty()) return;
    if (window.size() != 2 || window[0] < 1 || window[1] < window[0] || window[1] > snowflake_most_steps)
        run.refuse("restrict", "[first, last] with 1 <= first <= last <= " + std::to_string(snowflake_most_steps));
    restriction.first = static_cast<int>(window[0]);
    restriction.last = static_cast<int>(window[1]);
}

void read_priority_steps(Settings& run, sim::Priority& priority) {
    for (long long s : run.integers("priority", {})) {
        if (s < 1 || s > snowflake_most_steps)
            run.refuse("priority", "a list of steps, each from 1 to " + std::to_string(snowflake_most_steps));
        priority.steps.push_back(static_cast<int>(s));
    }
}

// Run i, read through a Settings of its own so that its mistakes name
// "params.runs[i].key"; params.rule, when given, replaces its rule.
SnowflakeRun read_run(const toml::table& table, std::size_t i, const sim::SnowflakeParams& shared, bool override_rule) {
    Settings run("params.runs[" + std::to_string(i) + "]", table, run_keys);
    SnowflakeRun r;
    std::string letter = "(a)";
    letter[1] = static_cast<char>('a' + i % 26);
    r.label = run.text("label", letter);
    r.params = shared;
    if (!override_rule) {
        const std::string code = run.text("rule", shared.rule.code());
        check_model(run, [&] { r.params.rule = sim::SnowflakeRule::parse(code); });
    }
    read_restriction_window(run, r.params.restriction);
    read_priority_steps(run, r.params.priority);
    check_model(run, [&] { r.params.validate(); },
                {{"restriction.first", "restrict"}, {"restriction.last", "restrict"}, {"priority.steps", "priority"}});
    r.used = run.used();
    r.used["rule"] = r.params.rule.code();
    return r;
}

}  // namespace

std::vector<Key> snowflake_keys(std::vector<Key> extra) {
    std::vector<Key> keys = {
        {"runs", "list of runs, e.g. [{rule = \"0101010\", label = \"(a)\"}]"},
        {"rule", "rule code for every run, replacing the runs' own"},
        {"steps", "steps of every run, 0.." + std::to_string(snowflake_most_steps)},
        {"restrict_radius", "restriction applies from this hex distance out, >= 1"},
        {"restrict_half_angle", "half-width in degrees of each forbidden wedge, (0, 30]"},
        {"priority_width", "cells beside each tip forced too, >= 0"},
        {"priority_exclusive",
         "true: during a priority step only the tips grow (the rule rests); false: they grow as well"},
    };
    keys.insert(keys.end(), extra.begin(), extra.end());
    return keys;
}

std::vector<SnowflakeRun> read_snowflake_runs(Settings& params) {
    const auto tables = params.tables("runs");
    if (params.has("runs") && tables.empty())
        params.refuse("runs", "one run at least, e.g. [{rule = \"0101010\"}]; leave runs out for one run of the "
                              "default rule");
    const bool override_rule = params.has("rule");
    const sim::SnowflakeParams shared = read_shared(params);
    std::vector<SnowflakeRun> runs;
    const std::size_t count = std::max<std::size_t>(tables.size(), 1);
    for (std::size_t i = 0; i < count; ++i)
        runs.push_back(read_run(i < tables.size() ? tables[i] : toml::table{}, i, shared, override_rule));
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

int snowflake_radius_bound(const sim::SnowflakeParams& p, int steps) {
    if (p.rule.freeze[1]) return steps;
    return static_cast<int>(
        std::count_if(p.priority.steps.begin(), p.priority.steps.end(), [&](int s) { return s <= steps; }));
}

double snowflake_cells_within(int radius) { return 3.0 * radius * (radius + 1.0) + 1.0; }

double snowflake_crystal_bytes(int radius) {
    return sim::Snowflake::storage_peak_bytes(radius) +
           (16.0 + 24.0) * sizeof(sim::HexCell) / 8.0 * snowflake_cells_within(radius);
}

std::string snowflake_hash(const sim::Snowflake& crystal) {
    std::vector<sim::HexCell> cells = crystal.ice_cells();
    std::sort(cells.begin(), cells.end(), [](auto a, auto b) { return a.r != b.r ? a.r < b.r : a.q < b.q; });
    std::vector<std::int32_t> flat;
    for (auto c : cells) {
        flat.push_back(c.q);
        flat.push_back(c.r);
    }
    return base::sha256_hex(flat.data(), flat.size() * sizeof(std::int32_t));
}

}  // namespace scenes
