#pragma once
// A formula model (sim/formula/rule.hpp), or a kernel rule
// (sim/kernel/run.hpp: params.kernel in place of params.formula), as a
// description gives it in [params]:
// the rule (chemicals, formula, accuracy, wrap, data_type, block_x,
// ready_edges, arithmetic), the grid (width, height, depth), steps, the start (initial:
// Ready's overlays, in order; or the arrays a Ready pattern file stores)
// and, as every other key, the rule's own parameters. Shared by the
// formula scene and the formula atlas.

#include <algorithm>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "scenes/scene.hpp"
#include "sim/formula/overlays.hpp"
#include "sim/formula/run.hpp"
#include "sim/grid.hpp"
#include "sim/kernel/run.hpp"

namespace scenes {

// The most cells a side of a formula model's grid has, and the most cells
// it has in all (4096^2, or 256^3).
constexpr int formula_most_side = 4096;
constexpr long long formula_most_cells = 4096LL * 4096LL;

struct FormulaModel {
    sim::formula::Rule rule;
    // The grid: height 1 is 1-D, depth above 1 is 3-D (the row of (y, z) is z * height + y).
    int width = 128, height = 128, depth = 1, steps = 1000;
    // Its error measured (scenes/formula.cpp's error_said): none; in time;
    // in time and in space (a run at twice the resolution too).
    enum class Error { none, time, space };
    Error error = Error::none;
    sim::formula::Pattern pattern;
    int registers = 0, radius_x = 0;  // of the compiled formula, for the memory estimate
    int radius_y = 0, radius_z = 0;
    int operations = 0;               // row operations a cell of one step takes (Run::operations)
    double machine_code = 0;          // bytes of its chains' machine code (sim/formula/chain_kernels.hpp)
    // A kernel rule: the whole OpenCL kernel the rule is, in place of the
    // formula (rule.chemicals, rule.double_precision and rule.block_x say
    // its chemicals, numbers and blocks); the registers a thread keeps for it.
    std::optional<sim::kernel::ImageRule> kernel;
    long long kernel_thread_bytes = 0;
};

// A run of the model's rule: its formula (sim/formula/run.hpp) or its
// kernel (sim/kernel/run.hpp). A kernel's failure is formula::Unstable,
// as a formula's.
class RuleRun {
public:
    RuleRun(const FormulaModel& m, const std::vector<sim::Grid<double>>& start);
    void step(int steps, int threads = 0);
    sim::Grid<double> chemical(int i) const;
    long long steps() const;
    int operations() const;

private:
    std::optional<sim::formula::Run> formula_;
    std::optional<sim::kernel::ImageRun> kernel_;
};

// [params]'s keys: the rule's, the scene's own (`scene_keys`), and every
// other key of d.params as a parameter of the rule.
std::vector<Key> formula_param_keys(const Description& d, const std::vector<Key>& scene_keys = {});

// The rule's chemicals as the description gives them (2 if not; its reader
// checks the number): the style has keys for these alone.
int formula_chemicals(const Description& d);

// `name`, read from `key` (one of a list when `listed`), as a chemical's
// index; refuses anything but one of the rule's `chemicals`.
int chemical_index(Settings& s, const std::string& key, const std::string& name, int chemicals, bool listed = false);

// The names `code` reads, from its tree; refuses (as params.formula) a
// formula that does not parse, naming its line and column.
std::set<std::string> formula_names(Settings& params, const std::string& code);

// Refuses (as params.NAME) a parameter's name that the rule cannot take
// (sim/formula/names.hpp), naming the clash: the one check of a
// parameter's name, for descriptions and Ready's files alike.
void refuse_clash(Settings& params, const std::string& name, int chemicals);

// Reads and checks the model, compiling its formula (refusals name the
// formula's line and column). `scene_keys` are not rule parameters;
// `swept` parameters (name, a value in range) are added to the rule's and
// may not be given in [params].
FormulaModel read_formula_model(Settings& params, const Description& d, const std::vector<Key>& scene_keys = {},
                                const std::vector<std::pair<std::string, double>>& swept = {});

// The most ghost rows a run keeps past dirichlet sides (sim/formula/run.cpp),
// for the memory estimates: each plane's rows past its two y sides, each z
// row's past the two z sides, and the corners.
inline double formula_ghost_rows(const FormulaModel& m) {
    return m.rule.edges ? 2.0 * (m.radius_y * m.depth + m.radius_z * m.height) + 4.0 * m.radius_y * m.radius_z : 0;
}

// The start: the stored arrays of a Ready pattern, and the overlays drawn
// with the description's seed (each cell moved by `offset` cells: see
// sim::formula::apply_pattern).
std::vector<sim::Grid<double>> formula_start(const FormulaModel& m, const Description& d,
                                             std::array<double, 3> offset = {0, 0, 0});

// The overlays of params.initial (a list of tables), read for `rule`'s
// chemicals and parameters: the mesh scene's start, as a formula model's.
std::vector<sim::formula::Overlay> read_overlays(const std::vector<toml::table>& initial, const sim::formula::Rule& rule);

// A 1-D run's space-time diagram keeps the row of every stride-th step up
// to `last` (and the last): the least stride that keeps at most `rows`.
inline int space_time_stride(int last, int rows) { return std::max(1, (last + rows - 1) / rows); }

}  // namespace scenes
