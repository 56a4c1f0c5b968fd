#include "scenes/helpers/snowflake_setup.hpp"

#include <algorithm>

#include "base/digest.hpp"
#include "scenes/helpers/model_check.hpp"

namespace scenes {
namespace {

// One run's keys, over the shared ones.
struct RunValues {
    std::string label;
    sim::SnowflakeParams params;
    bool rule_given = false;  // [params] gives the rule: the run's own is not read
};

const std::string restrict_allowed = "[first, last] with 1 <= first <= last <= " + std::to_string(snowflake_most_steps);
const std::string priority_allowed = "a list of steps, each from 1 to " + std::to_string(snowflake_most_steps);

const Schema<RunValues> run_schema =
    Schema<RunValues>()
        .key({"rule", "7-digit rule code d0..d6, d0 = 0", "text"},
             [](Settings& run, const std::string& key, RunValues& v) {
                 if (v.rule_given) return;
                 const std::string code = run.text(key, v.params.rule.code());
                 check_model(run, [&] { v.params.rule = sim::SnowflakeRule::parse(code); });
             })
        .text("label", &RunValues::label, "panel letter, e.g. \"(a)\"")
        // Absent: no restriction.
        .key({"restrict", "[first, last]: steps during which freezing is forbidden in the gaps between the arms",
              "a list of integers", restrict_allowed},
             [](Settings& run, const std::string& key, RunValues& v) {
                 const auto window = run.integers(key, {});
                 if (window.empty()) return;
                 if (window.size() != 2 || window[0] < 1 || window[1] < window[0] || window[1] > snowflake_most_steps)
                     run.refuse(key, restrict_allowed);
                 v.params.restriction.first = static_cast<int>(window[0]);
                 v.params.restriction.last = static_cast<int>(window[1]);
             })
        .key(
            {"priority", "steps during which growth is forced at the six tips", "a list of integers", priority_allowed},
            [](Settings& run, const std::string& key, RunValues& v) {
                for (long long s : run.integers(key, {})) {
                    if (s < 1 || s > snowflake_most_steps) run.refuse(key, priority_allowed);
                    v.params.priority.steps.push_back(static_cast<int>(s));
                }
            })
        .check(validated(
            {{"restriction.first", "restrict"}, {"restriction.last", "restrict"}, {"priority.steps", "priority"}},
            [](RunValues& v) -> sim::SnowflakeParams& { return v.params; }));

// Run i, read through a Settings of its own so that its mistakes name
// "params.runs[i].key"; params.rule, when given, replaces its rule.
SnowflakeRun read_run(const toml::table& table, std::size_t i, const SnowflakeSetup& setup) {
    Settings run("params.runs[" + std::to_string(i) + "]", table, run_schema.keys());
    RunValues v;
    v.label = "(a)";
    v.label[1] = static_cast<char>('a' + i % 26);
    v.params = setup.shared;
    v.rule_given = setup.rule_given;
    v = run_schema.read(run, v);
    SnowflakeRun r{v.label, v.params, run.used()};
    r.used["rule"] = r.params.rule.code();
    return r;
}

// The keys every run shares (the rule, the restriction's region, the
// priority's width), checked by the model on a run made of them alone: a
// mistake there names the [params] key, not each run.
Schema<SnowflakeSetup> make_snowflake_schema() {
    using S = SnowflakeSetup;
    Schema<S> s;
    s.key({"runs", "list of runs, e.g. [{rule = \"0101010\", label = \"(a)\"}]", "a list of tables",
           "one run at least; absent: one run of the shared keys"},
          [](Settings& params, const std::string& key, S& v) {
              v.tables = params.tables(key);
              if (params.has(key) && v.tables.empty())
                  params.refuse(key,
                                "one run at least, e.g. [{rule = \"0101010\"}]; leave runs out for one run of the "
                                "default rule");
          });
    s.key(
        {"rule", "rule code for every run, replacing the runs' own", "text"},
        [](Settings& params, const std::string& key, S& v) {
            v.rule_given = params.has(key);
            const std::string code = params.text(key, v.shared.rule.code());
            check_model(params, [&] { v.shared.rule = sim::SnowflakeRule::parse(code); });
        },
        [](const S& d) { return nlohmann::json(d.shared.rule.code()); });
    Schema<sim::Restriction> restriction;
    restriction.count("restrict_radius", &sim::Restriction::min_radius,
                      "restriction applies from this hex distance out");
    restriction.number("restrict_half_angle", &sim::Restriction::half_angle,
                       "half-width in degrees of each forbidden wedge");
    Schema<sim::Priority> priority;
    priority.count("priority_width", &sim::Priority::width, "cells beside each tip forced too");
    priority.flag("priority_exclusive", &sim::Priority::exclusive,
                  "true: during a priority step only the tips grow (the rule rests); false: they grow as well");
    s.part_at(
        restriction, [](auto& v) -> auto& { return v.shared.restriction; });
    s.part_at(
        priority, [](auto& v) -> auto& { return v.shared.priority; });
    s.check(validated({{"restriction.min_radius", "restrict_radius"},
                       {"restriction.half_angle", "restrict_half_angle"},
                       {"priority.width", "priority_width"}},
                      [](S& v) -> sim::SnowflakeParams& { return v.shared; }));
    s.check([](Settings&, const std::string&, S& v) {
        const std::size_t count = std::max<std::size_t>(v.tables.size(), 1);
        for (std::size_t i = 0; i < count; ++i)
            v.runs.push_back(read_run(i < v.tables.size() ? v.tables[i] : toml::table{}, i, v));
    });
    return s;
}

}  // namespace

SnowflakeSetup::SnowflakeSetup() {
    shared.rule = sim::SnowflakeRule::parse("0101010");
    shared.restriction.min_radius = 2;
    shared.restriction.half_angle = 15.0;
    shared.priority.width = 0;
    shared.priority.exclusive = true;
}

const Schema<SnowflakeSetup>& snowflake_schema() {
    static const Schema<SnowflakeSetup> schema = make_snowflake_schema();
    return schema;
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
