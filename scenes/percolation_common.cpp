#include "scenes/percolation_common.hpp"

#include "base/digest.hpp"

namespace scenes {

Key stop_key() {
    return {"stop", "\"bottom_or_fixed_point\" or \"fixed_point\""};
}

StopRule read_stop(Settings& params) {
    const std::string stop = params.text("stop", "bottom_or_fixed_point");
    if (stop == "bottom_or_fixed_point") return StopRule::bottom_or_fixed_point;
    if (stop == "fixed_point") return StopRule::fixed_point;
    params.refuse("stop", "\"bottom_or_fixed_point\" (the book's test_perc) or \"fixed_point\"");
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
