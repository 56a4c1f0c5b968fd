#pragma once
// What the percolation scenes share: for the field scenes (percolation,
// percolation_sizes) how a run ends, what a panel's metadata records and the
// book's colours for the cells; for the plots (percolation_scaling,
// percolation_phase) the book's test_perc.

#include <nlohmann/json.hpp>

#include "scenes/description_names.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "sim/percolation.hpp"
#include "sim/random.hpp"

namespace scenes {

// How a run ends: the book's test_perc stops as soon as the bottom row is wet;
// the model's own fixed point comes later. Each figure says which it shows.
enum class StopRule { bottom_or_fixed_point, fixed_point };

// The [params] key `stop`, declared in `schema` and read into `member`.
template <class T>
void add_stop_key(Schema<T>& schema, StopRule T::*member) {
    schema.choice("stop", member,
                  {{"bottom_or_fixed_point", StopRule::bottom_or_fixed_point}, {"fixed_point", StopRule::fixed_point}},
                  "the book's test_perc (stop once the bottom row is wet) or the model's fixed point");
}

// The [params] key `p_c`: a known threshold, drawn as a line, so strictly inside (0, 1).
template <class T>
void add_p_c_key(Schema<T>& schema, double T::*member, const std::string& meaning) {
    const std::string allowed = "a number between 0 and 1, both excluded (a probability)";
    schema.key({"p_c", meaning, "a number", allowed, 0.59274621},
               [member, allowed](Settings& s, const std::string& key, T& v) {
                   v.*member = s.number_in(key, v.*member, 0.0, 1.0);
                   if (!(v.*member > 0 && v.*member < 1)) s.refuse(key, allowed);
               });
}

// The model's [params], n and q, checked by the model.
const Schema<sim::PercolationParams>& percolation_schema();

// One step under the stop rule: false once the run is over.
bool step_until_stop(sim::Percolation& model, StopRule stop);

// A panel's step, size, statistics and state hash, and why the run stopped
// when it has.
nlohmann::json panel_metadata(const sim::Percolation& model, StopRule stop, bool stopped);

// Blocked 0, porous 1, wet 5, drawn in Blues from 0 to 5.
FieldSpec default_percolation_spec();

// The book's test_perc on a fresh n x n model drawn from `rng`; `wet`, when
// given, receives the wet cells at the stop.
sim::PercolationRun test_perc(int n, double q, sim::Random& rng, long* wet = nullptr);

}  // namespace scenes
