#include "scenes/helpers/percolation_common.hpp"

#include "base/digest.hpp"
#include "scenes/helpers/model_check.hpp"

namespace scenes {

const Schema<sim::PercolationParams>& percolation_schema() {
    using P = sim::PercolationParams;
    static const Schema<P> schema = Schema<P>()
                                        .count("n", &P::n, "grid size")
                                        .number("q", &P::q, "probability that a cell is porous")
                                        .check(validated<P>());
    return schema;
}

bool step_until_stop(sim::Percolation& model, StopRule stop) {
    if (stop == StopRule::bottom_or_fixed_point && model.bottom_row_wet()) return false;
    return model.step() > 0;
}

nlohmann::json panel_metadata(const sim::Percolation& model, StopRule stop, bool stopped) {
    const auto& cells = model.cells();
    long porous = 0;
    for (auto c : cells.cells()) porous += c == sim::Percolation::porous;
    nlohmann::json meta = {
        {"step", model.steps()},
        {"n", cells.rows()},
        {"statistics", {{"wet", model.wet_count()}, {"porous_dry", porous}, {"percolates", model.bottom_row_wet()}}},
        {"state_sha256", base::sha256_hex(cells.data(), cells.size())},
    };
    if (stopped)
        meta["stopped"] =
            model.bottom_row_wet() && stop == StopRule::bottom_or_fixed_point ? "bottom row wet" : "fixed point";
    return meta;
}

FieldSpec default_percolation_spec() {
    return {render::colormap("Blues"), 0.0, 5.0, 0.6f, render::Sampling::nearest};
}

sim::PercolationRun test_perc(int n, double q, sim::Random& rng, long* wet) {
    sim::PercolationParams p;
    p.n = n;
    p.q = q;
    sim::Percolation model(p, rng);
    const auto run = sim::run_to_bottom_or_fixed_point(model);
    if (wet) *wet = model.wet_count();
    return run;
}

}  // namespace scenes
