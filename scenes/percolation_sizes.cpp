// Percolation clusters at several sizes (Think Complexity 2e, Fig 7.8). tc7-8:
// one run per size, each to its stop; the animation follows the last
// (largest) run's wetting front as it happens.
#include <algorithm>
#include <climits>

#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/percolation_common.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"
#include "sim/random.hpp"

namespace scenes {
namespace {

// Panels side by side in one row: more than this leaves each too small to read.
constexpr std::size_t most_sizes = 16;

struct Params {
    std::vector<long long> sizes{100, 200, 300};
    double q = 0.6;
    StopRule stop = StopRule::bottom_or_fixed_point;
    std::vector<sim::PercolationParams> runs;  // one per size, each checked by the model itself
};

const Schema<Params> param_schema = [] {
    Schema<Params> s;
    s.key(
        {"sizes", "grid sizes, one panel each", "a list of integers",
         "1 to " + std::to_string(most_sizes) + " grid sizes, one panel each"},
        [](Settings& section, const std::string& key, Params& p) {
            p.sizes = section.integers(key, p.sizes);
            if (p.sizes.empty() || p.sizes.size() > most_sizes)
                section.refuse(key, "1 to " + std::to_string(most_sizes) + " grid sizes, one panel each");
        },
        [](const Params& d) { return nlohmann::json(d.sizes); });
    s.number("q", &Params::q, "probability that a cell is porous");
    add_stop_key(s, &Params::stop);
    s.check([](Settings& section, const std::string&, Params& p) {
        for (long long n : p.sizes) {
            sim::PercolationParams run;
            // Clamped only so that the model sees (and refuses) a size beyond an int.
            run.n = static_cast<int>(std::clamp<long long>(n, INT_MIN, INT_MAX));
            run.q = p.q;
            check_model(section, [&] { run.validate(); }, {{"n", "sizes"}});
            p.runs.push_back(run);
        }
    });
    return s;
}();

class PercolationSizesScene : public SceneBase {
public:
    PercolationSizesScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), field_spec_schema().keys(default_percolation_spec())),
          p_(param_schema.read(params_)),
          spec_(field_spec_schema().read(style_, default_percolation_spec())) {}

    // The largest run's cells and their next step; each panel's field, kept
    // as doubles until the figure is drawn.
    std::vector<MemoryNeed> memory() const override {
        int largest = 0;
        std::vector<MemoryNeed> needs;
        for (const sim::PercolationParams& run : p_.runs) {
            largest = std::max(largest, run.n);
            needs.push_back(
                grid_need("a panel's doubles and texture", run.n, run.n, 8 + field_layer_bytes_per_cell, 1));
        }
        needs.push_back(grid_need("grids of bytes", largest, largest, 1, 2));
        return needs;
    }

    // One run per size, each to its stop, through one step runner: the film
    // follows the last (largest) run as its wetting front spreads.
    void render(Output& out) const override {
        StepRunner run(d_, options_, out);
        sim::Random rng(d_.seed);  // the runs draw from one stream, in order
        std::vector<FieldPanel> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        for (std::size_t i = 0; i < p_.runs.size(); ++i) {
            sim::Percolation model(p_.runs[i], rng);
            const bool filmed = i + 1 == p_.runs.size();
            run.run_to_stop(hooks(model, p_.runs[i].n, filmed, run));
            panels.push_back({titled(d_.panel_title, p_.runs[i].n, model), {field_layer(model.cells(), spec_)}});
            panel_meta.push_back(panel_metadata(model, p_.stop, true));
        }
        run.write_field_figure(panels, {{"params", params_.used()}, {"style", style_.used()}, {"panels", panel_meta}});
    }

private:
    // `pattern` with the run's {n} and the model's {step}.
    static std::string titled(const std::string& pattern, int n, const sim::Percolation& model) {
        return expand(pattern, {{"n", std::to_string(n)}, {"step", std::to_string(model.steps())}});
    }

    // The book's test_perc: the run stops when the bottom row is wet (under
    // that rule) or when a step changes nothing.
    StepHooks hooks(sim::Percolation& model, int n, bool filmed, StepRunner& run) const {
        StepHooks h;
        h.stopped = [&model, this] { return p_.stop == StopRule::bottom_or_fixed_point && model.bottom_row_wet(); };
        h.advance = [&model] { return model.step() > 0; };
        if (filmed)
            h.frame = [&model, &run, n, this](int) -> FrameDrawing {
                return run.field_frame(
                    {{titled(d_.animation->title, n, model), {field_layer(model.cells(), spec_)}}});
            };
        return h;
    }

    const Params p_;
    const FieldSpec spec_;
};

std::unique_ptr<Scene> read_percolation_sizes(const Description& d, const SceneOptions& options) {
    return std::make_unique<PercolationSizesScene>(d, options);
}

}  // namespace

SceneInfo percolation_sizes_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"percolation_sizes",
            read_percolation_sizes,
            {"colormap"},
            {
                {"/panels/*/step", "steps run, n = {n}", "integer", ""},
                {"/panels/*/statistics/wet", "wet cells, n = {n}", "integer", ""},
            }};
}

}  // namespace scenes
