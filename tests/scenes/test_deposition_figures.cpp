// The bd figures (ballistic deposition) as a user renders them, and the
// numbers they record.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"

using testkit::render_json;

TEST_CASE("bd-500 deposits L squared particles in as many cells", "[deposition-figure]") {
    const auto meta = render_json("bd-500", "");
    const auto& panel = meta["panels"][0];
    CHECK(panel["particles"] == 250000);
    CHECK(panel["cells"] == 250000);
    // Ballistic deposits are porous: about half the cells below the surface are full.
    CHECK(panel["packing_fraction"].get<double>() > 0.4);
    CHECK(panel["packing_fraction"].get<double>() < 0.6);
}

// KPZ: beta = 1/3, alpha = 1/2. Ballistic deposition's large intrinsic width
// lowers both at small sizes (published beta ~ 0.30; alpha well under 1/2
// below L ~ 1000), so the bounds here are wide but exclude 0 and 1.
TEST_CASE("bd-roughness fits beta and alpha near KPZ on small sizes", "[deposition-figure]") {
    const auto meta = render_json("bd-roughness", "--set widths=[64,128,256] --set seeds=3 --set beta_range=[2,30]");
    const double beta = meta["beta"]["value"], alpha = meta["alpha"]["value"];
    CHECK(beta > 0.2);
    CHECK(beta < 0.4);
    CHECK(alpha > 0.15);
    CHECK(alpha < 0.6);
    CHECK(meta["curves"].size() == 3);
}
