// The formula scene (scenes/formula.cpp): a rule of the user's own runs into
// a figure; tc7-2 written as a formula gives tc7-2's fields bit for bit;
// every mistake in a description is refused before anything runs.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/render/render_figure.hpp"
#include "description/catalog.hpp"
#include "description/description.hpp"
#include "figgen_run.hpp"
#include "scenes/scene.hpp"

namespace fs = std::filesystem;

namespace {

nlohmann::json render_small(const description::Description& d, bool error = false) {
    app::OutputOptions options;
    options.error = error;
    options.dir = fs::path(FIGGEN_TEST_ARTIFACT_DIR) / ("formula-scene-" + std::to_string(::getpid()));
    options.scale = 0.25;
    options.video = false;
    scenes::Progress quiet;
    app::render_figure(d, options, quiet);
    std::ifstream in(options.dir / (d.id + ".json"));
    auto meta = nlohmann::json::parse(in);
    fs::remove_all(options.dir);
    return meta;
}

const std::string rule = R"(
id = "fx-test"
title = "a test"
scene = "formula"
seed = 3
[params]
chemicals = 2
width = 32
height = 32
steps = 100
formula = "delta_a = D_a * laplacian_a - a*b*b + F*(1.0f-a);\ndelta_b = D_b * laplacian_b + a*b*b - (F+K)*b;"
timestep = 1.0
D_a = 0.2
D_b = 0.1
F = 0.035
K = 0.06
initial = [{chemical = "a", fill = "constant", value = 1.0, shapes = [{shape = "everywhere"}]}, {chemical = "b", fill = "constant", value = 0.25, shapes = [{shape = "circle", centre = [0.5, 0.5], radius = 0.1}]}]
[figure]
panels = [0, 100]
size = [400, 200]
)";

// The description above with one line of [params] replaced (or added).
std::string with(const std::string& key, const std::string& value) {
    std::string text = rule;
    const std::size_t at = text.find("\n" + key + " = ");
    if (at == std::string::npos) {
        const std::size_t params = text.find("[params]\n") + 9;
        return text.insert(params, key + " = " + value + "\n");
    }
    const std::size_t end = text.find('\n', at + 1);
    return text.replace(at + 1, end - at - 1, key + " = " + value);
}

std::string refusal(const std::string& text) {
    try {
        const auto d = description::parse_description(text, "fx-test.toml");
        scenes::read_scene(d, {});
    } catch (const description::UsageError& e) {
        return e.what();
    }
    return "accepted";
}

}  // namespace

TEST_CASE("tc7-2 written as a formula gives tc7-2's fields bit for bit", "[formula][scenes]") {
    const auto book = render_small(description::load_description(description::resolve_figure("tc7-2")));
    const auto formula =
        render_small(description::load_description(fs::path(FIGGEN_SOURCE_DIR) / "figures/fx-tc7-2.toml"));
    REQUIRE(book["panels"].size() == 3);
    REQUIRE(formula["panels"].size() == 3);
    for (int i = 0; i < 3; ++i) {
        INFO("panel " << i);
        CHECK(formula["panels"][i]["step"] == book["panels"][i]["step"]);
        CHECK(formula["panels"][i]["state_sha256"] == book["panels"][i]["state_sha256"]);
    }
}

TEST_CASE("a formula description runs into panels, the start as its overlays make it", "[formula][scenes]") {
    const auto meta = render_small(description::parse_description(rule, "fx-test.toml"));
    REQUIRE(meta["panels"].size() == 2);
    // Step 0: A is 1 everywhere; B 0.25 on a circle of radius 3.2 cells around (16, 16), else 0.
    const auto& a0 = meta["panels"][0]["statistics"]["a"];
    CHECK(a0["min"] == 1.0);
    CHECK(a0["max"] == 1.0);
    const auto& b0 = meta["panels"][0]["statistics"]["b"];
    CHECK(b0["max"] == 0.25);
    CHECK(b0["min"] == 0.0);
    // 37 cells lie within 3.2 of (16, 16) (7 + 2 x 7 + 2 x 5 + 2 x 3 by columns): 0.25 each, over 1024.
    CHECK(b0["mean"].get<double>() == Approx(37 * 0.25 / 1024));
    CHECK(meta["panels"][1]["step"] == 100);
    CHECK(meta["model_operations"].get<int>() > 0);
}

TEST_CASE("a formula description's mistakes are refused, naming the key and the formula's line", "[formula][scenes]") {
    CHECK_THAT(refusal(with("formula", "\"delta_a = D_a * laplacian_a + F + K;\\ndelta_b = D_b * q;\"")),
               Catch::StartsWith("formula = ") &&
                   Catch::Contains("line 2, column 17 of the formula: 'q' is not a chemical"));
    CHECK_THAT(refusal(with("Q", "2.0")), Catch::StartsWith("Q = 2 is not allowed: a parameter the formula or an overlay uses"));
    CHECK_THAT(refusal(with("width", "30")), Catch::StartsWith("width = 30 is not allowed: a multiple of block_x (4)"));
    CHECK_THAT(refusal(with("D_a", "nan")), Catch::StartsWith("D_a = nan is not allowed"));
    CHECK_THAT(refusal(with("timestep", "inf")), Catch::StartsWith("timestep = inf is not allowed"));
    CHECK_THAT(refusal(with("steps", "50")), Catch::StartsWith("figure.panels = [0, 100] is not allowed"));
    CHECK_THAT(refusal(with("accuracy", "\"best\"")), Catch::StartsWith("accuracy = 'best' is not allowed"));
    CHECK_THAT(refusal(with("initial", "[{chemical = \"c\", shapes = [{shape = \"everywhere\"}]}]")),
               Catch::StartsWith("initial[0].chemical = 'c' is not allowed"));
    CHECK_THAT(refusal(with("initial", "[{fill = \"plasma\", shapes = [{shape = \"everywhere\"}]}]")),
               Catch::StartsWith("initial[0].fill = 'plasma' is not allowed"));
    CHECK_THAT(refusal(with("initial", "[{shapes = [{shape = \"blob\"}]}]")),
               Catch::StartsWith("initial[0].shapes[0].shape = 'blob' is not allowed"));
    CHECK_THAT(refusal(with("initial", "[{fill = \"parameter\", parameter = \"G\", shapes = [{shape = \"everywhere\"}]}]")),
               Catch::StartsWith("initial[0].parameter = 'G' is not allowed"));
    CHECK_THAT(refusal(with("initial", "[{shapes = []}]")), Catch::StartsWith("initial[0].shapes = [] is not allowed"));
    CHECK(refusal(rule) == "accepted");
}

TEST_CASE("a film past params.steps is refused, and not checked when no film is made", "[formula][scenes]") {
    const std::string shorter = with("steps", "50") + "[animation]\nsteps = [0, 100]\n";
    const std::string text = shorter.substr(0, shorter.find("panels = [0, 100]")) + "panels = [0, 50]" +
                             shorter.substr(shorter.find("panels = [0, 100]") + 17);
    const auto d = description::parse_description(text, "fx-test.toml");
    scenes::SceneOptions film;
    CHECK_THROWS_WITH(scenes::read_scene(d, film),
                      Catch::StartsWith("animation.steps = 100 is not allowed: steps up to params.steps (50)"));
    scenes::SceneOptions no_film;
    no_film.film = false;
    CHECK_NOTHROW(scenes::read_scene(d, no_film));
    const auto meta = render_small(d);  // --no-video: the panels run, to step 50 and no further
    REQUIRE(meta["panels"].size() == 2);
    CHECK(meta["panels"][1]["step"] == 50);
}

TEST_CASE("a formula description's edges: read, refused where they cannot be, and said in the metadata", "[formula][scenes]") {
    CHECK_THAT(refusal(with("edges", "\"sideways\"")),
               Catch::StartsWith("edges = 'sideways' is not allowed: \"periodic\", \"neumann\" or \"dirichlet\""));
    CHECK_THAT(refusal(with("edges", "{left = \"dirichlet\", right = \"periodic\"}")),
               Catch::Contains("the left side is dirichlet and the right side periodic: periodic goes on both sides"));
    CHECK_THAT(refusal(with("edges", "{middle = \"neumann\"}")), Catch::Contains("middle"));
    CHECK_THAT(refusal(with("edges", "\"dirichlet\"\nedge_value = [1, 2, 3]")),
               Catch::StartsWith("edge_value = [ 1, 2, 3 ] is not allowed: a number, or a list of one number a chemical (2)"));
    CHECK_THAT(refusal(with("edges", "\"dirichlet\"\nedge_value = nan")), Catch::StartsWith("edge_value = nan is not allowed"));
    CHECK(refusal(with("edges", "{left = \"dirichlet\", right = \"neumann\", top = \"neumann\", bottom = \"neumann\"}")) ==
          "accepted");

    // Given, the edges replace wrap and ready_edges, which are not read (nor said).
    const auto meta = render_small(description::parse_description(
        with("edges", "{left = \"dirichlet\", right = \"dirichlet\", bottom = \"neumann\", top = \"neumann\"}\n"
                      "edge_value = {left = [1.0, 0.0]}\nwrap = false"),
        "fx-test.toml"));
    CHECK(meta["edges"]["left"]["edge"] == "dirichlet");
    CHECK(meta["edges"]["left"]["value"] == nlohmann::json({1.0, 0.0}));
    CHECK(meta["edges"]["right"]["value"] == nlohmann::json({0.0, 0.0}));
    CHECK(meta["edges"]["top"]["edge"] == "neumann");
    CHECK(!meta["edges"].contains("front"));  // a 2-D grid has no front
    CHECK(!meta["params"].contains("wrap"));
    // Ready's edges where none are given.
    const auto plain = render_small(description::parse_description(rule, "fx-test.toml"));
    CHECK(plain["edges"] == nlohmann::json({{"ready", true}, {"wrap", true}}));
}

TEST_CASE("strict refuses a timestep past the stability bound before the run", "[formula][scenes]") {
    // Gray-Scott's a, D_a = 0.2, medium accuracy in 2-D: 0.375 / 0.2 = 1.875 under Euler.
    auto strict_refusal = [](const std::string& text) -> std::string {
        const auto d = description::parse_description(text, "fx-test.toml");
        scenes::SceneOptions options;
        options.strict = true;
        const auto scene = scenes::read_scene(d, options);
        try {
            scene->check_run();
        } catch (const description::UsageError& e) {
            return e.what();
        }
        return "accepted";
    };
    CHECK_THAT(strict_refusal(with("timestep", "2.0")),
               Catch::StartsWith("timestep = 2 is not allowed: at most 1.875, the explicit stability bound of euler") &&
                   Catch::Contains("integrator = \"rk4\""));
    CHECK(strict_refusal(with("timestep", "1.8")) == "accepted");
    // RK4 reaches 2.785 / (0.2 x 16/3) = 2.61: 2.0 is within it.
    CHECK(strict_refusal(with("timestep", "2.0\nintegrator = \"rk4\"")) == "accepted");
    // Without --strict the same description is read and runs (a warning on stderr).
    CHECK(refusal(with("timestep", "2.0")) == "accepted");
}

TEST_CASE("error in time measures each integrator's error in time and its order", "[formula][scenes]") {
    // The heat equation from a Gaussian, in double, to t = 8: its error in
    // time falls as the integrator's order says.
    const std::string heat = R"(
id = "fx-heat"
title = "heat"
scene = "formula"
[params]
chemicals = 1
data_type = "double"
width = 32
height = 32
steps = 40
formula = "delta_a = laplacian_a;"
timestep = 0.2
edges = "neumann"
initial = [{chemical = "a", fill = "gaussian", height = 1.0, sigma = 0.1, centre = [0.5, 0.5], shapes = [{shape = "everywhere"}]}]
[figure]
panels = [0, 40]
size = [400, 200]
)";
    struct Case {
        const char* integrator;
        int order;
    };
    for (const Case& c : {Case{"euler", 1}, Case{"heun", 2}, Case{"rk4", 4}}) {
        const auto meta = render_small(
            description::parse_description(heat + "", "fx-heat.toml",
                                           {std::string("params.integrator=\"") + c.integrator + "\""}),
            true);
        const auto& e = meta["error"];
        INFO(c.integrator << ": " << e.dump());
        CHECK(e["order"] == c.order);
        CHECK(e["step"] == 40);
        CHECK(e["timesteps"] == nlohmann::json({0.2, 0.1, 0.05}));
        const auto& a = e["chemicals"][0];
        CHECK(a["order"].get<double>() == Approx(c.order).margin(0.1));
        // Richardson: the figure's error is d1 2^q / (2^q - 1).
        const double d1 = a["largest"][0].get<double>(), q = c.order;
        CHECK(a["estimate"]["largest"].get<double>() == Approx(d1 * std::pow(2, q) / (std::pow(2, q) - 1)));
        CHECK(d1 > a["largest"][1].get<double>());
    }
    // Without --error, or error = true in [params], no error is measured.
    CHECK(!render_small(description::parse_description(heat, "fx-heat.toml"))["error"].is_object());
    CHECK(render_small(description::parse_description(heat, "fx-heat.toml", {"params.error=\"time\""}))["error"].is_object());
    // In float, RK4's differences are rounding: no order is said.
    const auto rounded = render_small(
        description::parse_description(heat, "fx-heat.toml", {"params.data_type=\"float\"", "params.integrator=\"rk4\""}),
        true);
    CHECK(rounded["error"]["chemicals"][0]["order"].is_null());
    CHECK(rounded["error"]["chemicals"][0].contains("rounding"));
}

TEST_CASE("error = space compares the run with one at twice the resolution: second order", "[formula][scenes]") {
    // 1-D heat from a Gaussian between neumann edges, to t = 10: at 64 and
    // 128 cells (dx 1 and 1/2, the timestep with dx^2) the difference from
    // the run at twice the resolution falls by 4.
    const std::string heat = R"(
id = "fx-heat1d"
title = "heat"
scene = "formula"
[params]
chemicals = 1
data_type = "double"
width = 64
height = 1
steps = 40
formula = "delta_a = laplacian_a;"
timestep = 0.25
dx = 1.0
edges = "neumann"
error = "space"
initial = [{chemical = "a", fill = "gaussian", height = 1.0, sigma = 0.1, centre = [0.5, 0.5], shapes = [{shape = "everywhere"}]}]
[figure]
panels = [0, 40]
size = [400, 200]
)";
    const auto coarse = render_small(description::parse_description(heat, "fx-heat1d.toml"));
    const auto fine = render_small(description::parse_description(
        heat, "fx-heat1d.toml",
        {"params.width=128", "params.dx=0.5", "params.timestep=0.0625", "params.steps=160", "figure.panels=[0,160]"}));
    const auto& space = coarse["error"]["space"];
    CHECK(space["grid"] == nlohmann::json({128, 1, 1}));
    CHECK(space["dx"] == nlohmann::json({1.0, 0.5}));
    const double d64 = space["chemicals"][0]["largest"].get<double>();
    const double d128 = fine["error"]["space"]["chemicals"][0]["largest"].get<double>();
    INFO("differences " << d64 << " and " << d128);
    CHECK(std::log2(d64 / d128) == Approx(2).margin(0.1));
    CHECK(space["chemicals"][0]["estimate"]["largest"].get<double>() == Approx(d64 * 4 / 3));
    // Where the finer run would not be the same model, it is refused before anything runs.
    CHECK_THAT(refusal(with("initial", "[{chemical = \"b\", fill = \"white_noise\", shapes = [{shape = "
                                       "\"everywhere\"}]}]\nerror = \"space\"")),
               Catch::StartsWith("error = \"space\" is not allowed: \"time\": \"space\" runs the model at twice the "
                                 "resolution, and initial[0]'s noise is drawn cell by cell"));
    CHECK_THAT(refusal(with("formula", "\"delta_a = a_n - a + D_a * F * K;\\ndelta_b = D_b * b;\"\nerror = \"space\"")),
               Catch::Contains("the formula reads a_n, a neighbour a cell away whatever dx is"));
    CHECK_THAT(refusal(with("error", "\"roughly\"")),
               Catch::StartsWith("error = 'roughly' is not allowed: \"none\", \"time\" or \"space\""));
}
