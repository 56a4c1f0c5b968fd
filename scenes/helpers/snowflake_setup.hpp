#pragma once
// The snowflake runs a description asks for, read from its [params]:
//
//   runs = [{rule = "0100000", restrict = [1, 16], label = "(a)"},
//           {rule = "0110100", restrict = [5, 22]}]    one crystal each
//   rule  = "0101010"     replaces every run's rule (e.g. --set rule=0110000)
//   steps = 40            steps of every run
//   restrict_radius, restrict_half_angle, priority_width: see sim/snowflake.hpp
//
// A run's keys: rule, label, restrict = [first, last] (freezing forbidden in
// the gaps between the arms during those steps), priority = [steps...]
// (growth forced at the six tips during those steps).

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "description/schema.hpp"
#include "scenes/description_names.hpp"
#include "sim/snowflake.hpp"

namespace scenes {

struct SnowflakeRun {
    std::string label;  // "(a)", "(b)", ...
    sim::SnowflakeParams params;
    nlohmann::json used;  // the run's settings as read, for the metadata
};

// The most steps a crystal is grown (steps, restrict and priority steps,
// panels): it grows up to a ring a step, and its store with it. One crystal
// of 4000 rings is estimated at 2.8 GiB (snowflake_crystal_bytes; sf87-6
// peaked at 2.0 GiB), what --max-memory 4G serves; 100,000 would need 2 TiB.
inline constexpr int snowflake_most_steps = 4000;

// The runs and the keys every run shares, as [params] gives them.
struct SnowflakeSetup {
    SnowflakeSetup();  // the shared keys' defaults: rule 0101010, gaps from ring 2 at 15 degrees, exclusive tips
    std::vector<toml::table> tables;  // the runs as given (none: one run of the shared keys)
    sim::SnowflakeParams shared;      // rule, restriction region, priority width and exclusiveness
    bool rule_given = false;          // [params] rule replaces every run's own
    std::vector<SnowflakeRun> runs;   // read and checked, the model's own check included
};

// Their keys, for a scene's [params] schema to take as a part (the scene
// adds steps). Mistakes name the key as written: "params.rule",
// "params.runs[2].restrict", "params.restrict_half_angle".
const Schema<SnowflakeSetup>& snowflake_schema();

// The restriction and priority of a run, for the metadata.
nlohmann::json snowflake_settings(const sim::SnowflakeParams& p);

// Memory estimates, before anything grows. The radius a run's crystal can
// reach in `steps` steps: a ring a step when d1 = 1 (the cell beyond each tip
// has one ice neighbour), else only the priority steps' forced tips.
int snowflake_radius_bound(const sim::SnowflakeParams& p, int steps);
// Cells within hex distance `radius` of the seed: the most ice it can hold.
double snowflake_cells_within(int radius);
// A crystal of that radius: its store at its peak, its list of ice cells
// (16 bytes a cell while it doubles) and the copies a panel, a frame or
// the hash makes of the list (24 bytes a cell while they grow).
double snowflake_crystal_bytes(int radius);

// SHA-256 of the ice cells in a fixed order: the crystal's identity.
std::string snowflake_hash(const sim::Snowflake& crystal);

}  // namespace scenes
