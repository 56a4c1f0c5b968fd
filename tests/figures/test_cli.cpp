// The figgen command's behaviour as a user sees it: exit status, one-line
// errors naming what is wrong and what is allowed, and no output files left
// by a failed run.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"
#include "render/png_io.hpp"
#include "render/video.hpp"

namespace fs = std::filesystem;

using testkit::figgen;
using testkit::fresh_dir;
using testkit::Run;

TEST_CASE("figgen list names tc7-1 with its title", "[cli]") {
    const Run run = figgen("list");
    CHECK(run.status == 0);
    CHECK_THAT(run.output, Catch::Contains("tc7-1") && Catch::Contains("Diffusion"));
}

TEST_CASE("figgen --help documents render's options", "[cli]") {
    const Run run = figgen("render --help");
    CHECK(run.status == 0);
    for (const char* option : {"--out", "--set", "--seed", "--scale", "--no-video", "--frames"})
        CHECK_THAT(run.output, Catch::Contains(option));
}

TEST_CASE("bad input gets one line naming the problem and what is allowed, exit status 2", "[cli]") {
    const fs::path out = fresh_dir("errors");
    const std::string render = "render --out " + out.string() + " --no-video ";
    struct Case {
        std::string args;
        std::string expected;
    };
    const Case cases[] = {
        {render + "tc7-99", "unknown figure id 'tc7-99'; closest: tc7-9, tc7-1, tc7-2 (`figgen list` shows all"},
        {render + "gs-atlass", "unknown figure id 'gs-atlass'; closest: gs-atlas, "},
        {render + "sf87-7", "unknown figure id 'sf87-7'; closest: sf87-2, sf87-3, sf87-4"},
        {render + "lycopodium", "unknown figure id 'lycopodium'; closest: pl-lsys-lycopodium, "},
        {render + "tc7-1 --set r=0.5", "r = 0.5 is not allowed: r must be a number from 0 to 0.25 (the explicit 5-point update's stability bound; beyond it the checkerboard grows)"},
        {render + "tc7-1 --set r=nan", "params.r = nan is not allowed: expected a finite number"},
        {render + "tc7-1 --set n=-3", "n = -3 is not allowed: n must be an integer from 1 to 8192"},
        {render + "tc7-1 --set n=2.5", "params.n = 2.5 is not allowed: expected an integer"},
        {render + "tc7-1 --set bogus=1", "unknown key params.bogus; allowed: n, r, boundary"},
        {render + "tc7-1 --set boundary=torus", "boundary = \"torus\" is not allowed: use \"zero\" or \"wrap\""},
        {render + "tc7-1 --set style.colormap=jet", "colormap \"jet\" is unknown: allowed are Reds"},
        {render + "tc7-1 --set figure.panels=[5,0]", "figure.panels must be in ascending order"},
        {render + "tc7-1 --set animation.fps=0", "animation.fps = 0 is not allowed"},
        {render + "tc7-1 --scale -1", "--scale -1 is not allowed: use a number from 0.1 to 8"},
        {render + "tc7-1 --scale nan", "--scale nan is not allowed"},
        {render + "tc7-1 --seed -5", "--seed"},
        {render + "tc7-1 --frobnicate", "--frobnicate"},
        {"render --out /dev/null/sub tc7-1", "--out /dev/null/sub: cannot create the folder"},
        {"", "A subcommand is required"},
    };
    for (const Case& c : cases) {
        INFO("figgen " << c.args);
        const Run run = figgen(c.args);
        CHECK(run.status == 2);
        CHECK(run.lines() == 1);
        CHECK_THAT(run.output, Catch::StartsWith("figgen: error: ") && Catch::Contains(c.expected));
    }
    CHECK(fs::is_empty(out));  // nothing written, not even a temporary
}

TEST_CASE("a malformed description names the file and line", "[cli]") {
    const fs::path dir = fresh_dir("malformed");
    std::ofstream(dir / "broken.toml") << "id = \"broken\"\nmodel = \"diffusion\"\n[params\nn = 3\n";
    const Run run = figgen("render --out " + dir.string() + " " + (dir / "broken.toml").string());
    CHECK(run.status == 2);
    CHECK_THAT(run.output, Catch::Contains("broken.toml:3"));

    std::ofstream(dir / "unknown-model.toml") << "id = \"x\"\nmodel = \"lava-lamp\"\n[figure]\npanels = [0]\n";
    const Run unknown = figgen("render --out " + dir.string() + " " + (dir / "unknown-model.toml").string());
    CHECK(unknown.status == 2);
    CHECK_THAT(unknown.output, Catch::Contains("model \"lava-lamp\" is unknown; allowed: diffusion"));
}

TEST_CASE("render writes the PNG with its text chunks and the metadata JSON, and nothing else", "[cli]") {
    const fs::path out = fresh_dir("render");
    const Run run = figgen("render tc7-1 --no-video --seed 9 --set r=0.2 --out " + out.string());
    REQUIRE(run.status == 0);
    CHECK(run.output.empty());  // stderr is not a terminal: no progress bar
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(out)) files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());
    CHECK(files == std::vector<std::string>{"tc7-1.json", "tc7-1.png"});

    const auto png = render::read_png(out / "tc7-1.png");
    CHECK(png.image.width == 900);
    CHECK(png.image.height == 450);
    auto chunk = [&](const std::string& key) {
        for (const auto& [k, v] : png.text)
            if (k == key) return v;
        return std::string("(missing)");
    };
    CHECK(chunk("figgen:seed") == "9");
    CHECK_THAT(chunk("figgen:params"), Catch::Contains("\"r\":0.2"));

    std::ifstream in(out / "tc7-1.json");
    const auto meta = nlohmann::json::parse(in);
    CHECK(meta["id"] == "tc7-1");
    CHECK(meta["seed"] == 9);
    CHECK(meta["params"]["r"] == 0.2);
    CHECK(meta["params"]["boundary"] == "zero");
    REQUIRE(meta["panels"].size() == 3);
    CHECK(meta["panels"][0]["step"] == 0);
    CHECK(meta["panels"][2]["step"] == 15);
    // Step 0 is the initial block: nine cells of 1.
    CHECK(meta["panels"][0]["statistics"]["sum"] == 9.0);
    CHECK(meta["panels"][0]["statistics"]["max"] == 1.0);
    CHECK(meta["panels"][0]["state_sha256"].get<std::string>().size() == 64);
    CHECK(meta["panels"][1]["state_sha256"] != meta["panels"][2]["state_sha256"]);
    CHECK_FALSE(meta.contains("animation"));
}

TEST_CASE("render with --frames writes the animation as a numbered PNG sequence", "[cli]") {
    const fs::path out = fresh_dir("frames");
    const Run run = figgen("render tc7-1 --no-video --frames --scale 0.25 --set animation.steps=[0,9] --out " +
                           out.string());
    REQUIRE(run.status == 0);
    int count = 0;
    for (const auto& entry : fs::directory_iterator(out / "tc7-1-frames")) {
        CHECK(entry.path().extension() == ".png");
        ++count;
    }
    CHECK(count == 10);
    const auto last = render::read_png(out / "tc7-1-frames" / "00009.png");
    CHECK(last.image.width == 120);  // 480 * 0.25
    CHECK(last.image.height == 130);
    std::ifstream in(out / "tc7-1.json");
    const auto meta = nlohmann::json::parse(in);
    CHECK(meta["animation"]["frames"] == 10);
    CHECK(meta["animation"]["png_sequence"] == "tc7-1-frames");
}

TEST_CASE("render writes an MP4 that decodes to every animation step", "[cli]") {
    const fs::path out = fresh_dir("video");
    const Run run = figgen("render tc7-1 --scale 0.5 --out " + out.string());
    REQUIRE(run.status == 0);
    const auto info = render::probe_video(out / "tc7-1.mp4");
    CHECK(info.frames == 61);  // steps 0..60
    CHECK(info.width == 240);
    CHECK(info.height == 260);
    CHECK(info.pixel_format == "yuv420p");
    CHECK(info.codec == "h264");
    CHECK(info.duration_seconds == Approx(6.1).margin(1e-6));  // 61 frames at 10 fps
    // The first frame is step 0: the block's centre is Reds' darkest colour
    // at alpha 0.8 over white, (133, 51, 61), give or take the YUV round trip.
    const render::Image first = render::decode_frame(out / "tc7-1.mp4", 0);
    const std::uint8_t* centre = first.pixel(first.width / 2, first.height / 2 + 10);
    CHECK(int(centre[0]) == Approx(133).margin(8));
    CHECK(int(centre[1]) == Approx(51).margin(8));
    CHECK(int(centre[2]) == Approx(61).margin(8));
}

TEST_CASE("a run that goes unstable stops at the step it went bad and writes nothing", "[cli]") {
    const fs::path out = fresh_dir("unstable");
    // Strong feed, fast diffusion of both, a saturated start: A leaves [0, 1] at once.
    const Run run = figgen("render tc7-2 --out " + out.string() +
                           " --set n=20 --set ra=1 --set rb=1 --set f=0.2 --set k=0 --set noise=1 --set island=1");
    CHECK(run.status == 1);
    CHECK_THAT(run.output, Catch::StartsWith("figgen: error: gray_scott (A) went numerically unstable at step 2") &&
                               Catch::Contains("no image written"));
    CHECK(fs::is_empty(out));  // no PNG, no JSON, no MP4, no temporaries
}
