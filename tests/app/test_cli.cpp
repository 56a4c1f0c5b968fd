// The figgen command's behaviour as a user sees it: exit status, one-line
// errors naming what is wrong and what is allowed, and no output files left
// by a failed run.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"
#include "media/png_io.hpp"
#include "media/video.hpp"

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

namespace {

// Every file under `dir` with its bytes: what "nothing created or changed" compares.
std::map<std::string, std::string> folder_contents(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        std::ifstream in(entry.path(), std::ios::binary);
        files[fs::relative(entry.path(), dir).string()] =
            std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    return files;
}

}  // namespace

TEST_CASE("bad input gets one line naming the problem and what is allowed, exit status 2", "[cli]") {
    const fs::path out = fresh_dir("errors");
    // Earlier outputs of a figure the bad inputs name: they must stay as they are.
    REQUIRE(figgen("render tc7-1 --out " + out.string()).status == 0);
    const auto before = folder_contents(out);
    const fs::path files = fresh_dir("error-descriptions");
    auto description = [&](const std::string& name, const std::string& text) {
        std::ofstream(files / name) << text;
        return (files / name).string();
    };
    const std::string head = "id = \"mine\"\nscene = \"diffusion\"\n";
    const std::string render = "render --out " + out.string() + " --no-video ";
    struct Case {
        std::string args;
        std::string expected;
    };
    const Case cases[] = {
        // The command line.
        {"", "A subcommand is required"},
        {"bogus-command",
         "unknown command 'bogus-command'; allowed: list, describe, convert, gallery, thumbnails, render"},
        {"list extra", "The following argument was not expected: extra"},
        {"render --out " + out.string(), "figures is required"},
        {render + "tc7-1 --frobnicate", "--frobnicate"},
        {render + "tc7-1 --scale -1", "--scale -1 is not allowed: use a number from 0.1 to 8"},
        {render + "tc7-1 --scale nan", "--scale nan is not allowed"},
        {render + "tc7-1 --scale 0", "--scale 0 is not allowed"},
        {render + "tc7-1 --scale 100", "--scale 100 is not allowed"},
        {render + "tc7-1 --seed -5", "--seed"},
        {render + "tc7-1 --seed abc", "--seed: abc is not allowed: use an integer from 0 to 9223372036854775807"},
        {render + "tc7-1 --seed 99999999999999999999",
         "--seed: 99999999999999999999 is not allowed: use an integer from 0 to 9223372036854775807"},
        {render + "tc7-1 --max-memory 10q", "--max-memory 10q is not allowed: use a size from 1 byte to 1 PiB"},
        {render + "tc7-1 --max-memory 0", "--max-memory 0 is not allowed: use a size from 1 byte to 1 PiB"},
        {render + "tc7-1 --max-memory -1", "--max-memory -1 is not allowed: use a size from 1 byte to 1 PiB"},
        {render + "tc7-1 --max-disk -5M", "--max-disk -5M is not allowed: use a size from 1 byte to 1 PiB"},
        {render + "tc7-1 --max-disk 99999999999999999999999",
         "--max-disk 99999999999999999999999 is not allowed: use a size from 1 byte to 1 PiB"},
        {render + "tc7-1 --max-disk lots", "--max-disk"},
        {"render --no-video --out /dev/null/sub tc7-1", "--out /dev/null/sub: cannot create the folder"},
        {"render --no-video --out /proc/figgen-out tc7-1", "--out /proc/figgen-out: cannot create the folder"},
        {render + "tc7-99", "unknown figure id 'tc7-99'; closest: tc7-9, tc7-1, tc7-2 (`figgen list` shows all"},
        {render + "gs-atlass", "unknown figure id 'gs-atlass'; closest: gs-atlas, "},
        {render + "sf87-7", "unknown figure id 'sf87-7'; closest: sf87-2, sf87-3, sf87-4"},
        {render + "lycopodium", "unknown figure id 'lycopodium'; closest: pl-lsys-lycopodium, "},
        {render + "/nonexistent/my.toml", "figure file /nonexistent/my.toml does not exist"},
        {render + "tc7-1 --size 10by20", "--size 10by20 is not allowed: use WIDTHxHEIGHT, each 2..16384"},
        {render + "tc7-1 --size 1x5", "--size 1x5 is not allowed"},
        {render + "tc7-1 --fps 0", "--fps: 0 is not allowed: use an integer from 1 to 120"},
        {render + "tc7-9 --fps 5", "--fps: none of the figures named has an animation"},
        {render + "tc7-1 --cmap jet",
         "--cmap jet is not allowed: use one of Reds, Blues, Greens, viridis, inferno, magma, plasma, cividis"},
        {render + "tc7-9 --cmap viridis",
         "--cmap: tc7-9 (scene percolation_scaling) draws no field to colour; the field scenes are diffusion, "},
        {render + "tc7-1 --format gif", "--format: gif is not allowed: use png, pdf, svg, mp4, webm, frames, vti, vtu"},
        {render + "tc7-1 --format png,eps", "--format: eps is not allowed: use png, pdf, svg, mp4, webm, frames, vti, vtu"},
        {render + "tc7-1 --format mp4", "--format mp4 is not allowed with --no-video or --frames: use one"},
        {render + "tc7-1 --format pdf,svg", "--format pdf,svg is not allowed with --no-video or --frames: use one"},
        {render + "tc7-1 --set 'figure.formats=[\"eps\"]'",
         "--set figure.formats=[\"eps\"]: figure.formats = [ 'eps' ] is not allowed: a list of \"pdf\", \"svg\" and "
         "\"png\""},
        {render + "tc7-1 --set figure.formats=pdf",
         "figure.formats = 'pdf' is not allowed: expected a list of strings"},
        // --set itself.
        {render + "tc7-1 --set r", "--set r: expected key=value, e.g. --set r=0.2"},
        {render + "tc7-1 --set =5", "--set =5: expected key=value"},
        {render + "tc7-1 --set nosuch.key=1",
         "--set nosuch.key=1: unknown section 'nosuch'; allowed: params, style, figure, animation"},
        {render + "tc7-1 --set bogus=1", "--set bogus=1: unknown key params.bogus; allowed: n, r, boundary"},
        // [figure] and [animation], including windows outside the run.
        {render + "tc7-1 --set figure.panels=[5,0]",
         "--set figure.panels=[5,0]: figure.panels = [ 5, 0 ] is not allowed: steps from 0 to 100000000, ascending, "
         "each once"},
        {render + "tc7-1 --set figure.panels=[-1]",
         "--set figure.panels=[-1]: figure.panels = [ -1 ] is not allowed: steps from 0 to 100000000, ascending"},
        {render + "tc7-1 --set figure.size=[1,1]",
         "--set figure.size=[1,1]: figure.size = [ 1, 1 ] is not allowed: [width, height], each 2..16384"},
        {render + "tc7-1 --set figure.size=3",
         "--set figure.size=3: figure.size = 3 is not allowed: expected a list of integers"},
        {render + "tc7-1 --set animation.fps=0",
         "--set animation.fps=0: animation.fps = 0 is not allowed: an integer from 1 to 120"},
        {render + "tc7-2 --set animation.fps=1000", "animation.fps = 1000 is not allowed"},
        {render + "tc7-2 --set animation.steps=[500,100]",
         "--set animation.steps=[500,100]: animation.steps = [ 500, 100 ] is not allowed: [first, last] with 0 <= "
         "first <= last <= 100000000"},
        {render + "tc7-2 --set animation.stride=0", "animation.stride = 0 is not allowed"},
        // The poster: a step of the film's window.
        {render + "tc7-2 --set animation.poster=7001",
         "--set animation.poster=7001: animation.poster = 7001 is not allowed: a step from 0 to 7000 "
         "(animation.steps); the poster is the frame at that step or the last before it"},
        {render + "tc7-1 --set animation.poster=-1", "animation.poster = -1 is not allowed: a step from 0 to 60"},
        {render + "tc7-1 --set animation.poster=last",
         "--set animation.poster=last: animation.poster = 'last' is not allowed: expected an integer"},
        {render + "tc7-1 --set animation.steps=[0,4]",
         "tc7-1.toml:39: animation.poster = 8 is not allowed: a step from 0 to 4 (animation.steps)"},
        {render + description("poster.toml", head + "[animation]\nsteps = [5, 10]\nstride = 5\nposter = 4\n"),
         "poster.toml:6: animation.poster = 4 is not allowed: a step from 5 to 10 (animation.steps); the poster is the "
         "frame at that step or the last before it"},
        {render + "tc7-6 --set figure.panels=[20000]",
         "--set figure.panels=[20000]: figure.panels = [20000] is not allowed: a step below 16384: each automaton at "
         "most 16384 rows (the renderer draws one field that large)"},
        // Memory and disk.
        {render + "tc7-1 --set n=8000 --max-memory 256M",
         "needs about 4.0 GiB of memory (grids of doubles 8000 x 8000 x 5: 2.4 GiB), more than --max-memory 256.0 MiB"},
        {render + "tc7-1 --set figure.size=[16000,16000]",
         "needs about 6.8 GiB of memory (figure 16000 x 16000 RGBA: 6.7 GiB), more than --max-memory 4.0 GiB"},
        {render + "pl-ifs-fern --set points=20000000 --max-memory 256M", "(3 x 20000000 points: 915.5 MiB)"},
        {render + "pl-lsys-3d --set depth=40",
         "--set depth=40: depth = 40 is not allowed: a depth within the turtle's budget (it would draw more than "
         "18,446,744,073,709,551,615 segments, more than the budget of 5,000,000)"},
        {"render --frames --out " + out.string() +
             " tc7-2 --max-disk 10M",  // 351 frames of 480 x 520 at 4 bytes, the MP4 at 0.15, its preview at most 2 MiB
                                       // and the 900 x 450 PNG: 350.3 MiB
         "its outputs would take up to about 350.3 MiB (mostly the PNG sequence), more than --max-disk 10.0 MiB"},
        {"render --format pdf,svg --out " + out.string() +
             " tc7-7 --max-disk 10M",  // the PNG at 4 bytes a pixel, the PDF and the SVG at 16 and 1 MiB each: 900 x
                                       // 450 x 36 + 2 MiB = 15.9 MiB, the PDF the largest part
         "its outputs would take up to about 15.9 MiB (mostly the PDF), more than --max-disk 10.0 MiB"},
        // diffusion
        {render + "tc7-1 --set r=0.5",
         "--set r=0.5: r = 0.5 is not allowed: a number from 0 to 0.25 (the explicit 5-point update's stability bound; "
         "beyond it the checkerboard grows)"},
        {render + "tc7-1 --set r=nan", "--set r=nan: r = nan is not allowed: expected a finite number"},
        {render + "tc7-1 --set n=-3", "--set n=-3: n = -3 is not allowed: an integer from 1 to 8192"},
        {render + "tc7-1 --set n=2.5", "--set n=2.5: n = 2.5 is not allowed: expected an integer"},
        {render + "tc7-1 --set boundary=torus",
         "--set boundary=torus: boundary = 'torus' is not allowed: \"zero\" or \"wrap\""},
        {render + "tc7-1 --set block_row=500",
         "--set block_row=500: block_row = 500 is not allowed: an integer from 0 to 6"},
        {render + "tc7-1 --set block_value=inf",
         "--set block_value=inf: block_value = inf is not allowed: expected a finite number"},
        {render + "tc7-1 --set style.colormap=jet",
         "--set style.colormap=jet: style.colormap = 'jet' is not allowed: one of Reds, Blues, Greens, viridis, "
         "inferno, magma, plasma, cividis"},
        // gray_scott and its atlas
        {render + "tc7-2 --set f=1.5", "--set f=1.5: f = 1.5 is not allowed: a number from 0 to 0.2"},
        {render + "tc7-2 --set ra=2",
         "--set ra=2: ra = 2 is not allowed: a number from 0 to 1 (the 9-point diffusion is monotone up to 1, no new "
         "extremes, and blows up beyond 1.25)"},
        {render + "tc7-3 --set n=0", "--set n=0: n = 0 is not allowed: an integer from 3 to 4096"},
        {render + "tc7-4 --set island=[1,2,3]",
         "--set island=[1,2,3]: island = [ 1, 2, 3 ] is not allowed: expected a number"},
        {render + "tc7-3 --set rb=\\\"fast\\\"", "--set rb=\"fast\": rb = 'fast' is not allowed: expected a number"},
        {render + "gs-atlas --set tiles=[0,5]",
         "--set tiles=[0,5]: tiles = 0 is not allowed: an integer from 1 to 256"},
        {render + "gs-atlas --set steps=-1",
         "--set steps=-1: steps = -1 is not allowed: an integer from 0 to 10000000"},
        // percolation, its sizes, scaling and phase
        {render + "tc7-5 --set q=1.5", "--set q=1.5: q = 1.5 is not allowed: a number from 0 to 1"},
        {render + "tc7-5 --set stop=\\\"never\\\"",
         "stop = 'never' is not allowed: \"bottom_or_fixed_point\" or \"fixed_point\""},
        {render + "tc7-8 --set sizes=[]",
         "--set sizes=[]: sizes = [] is not allowed: 1 to 16 grid sizes, one panel each"},
        {render + "tc7-8 --set q=nan", "--set q=nan: q = nan is not allowed: expected a finite number"},
        {render + "tc7-9 --set sizes=[10,-20]",
         "--set sizes=[10,-20]: sizes = [ 10, -20 ] is not allowed: [first, last] with 2 <= first <= last <= 4096"},
        {render + "tc7-phase --set trials=0", "--set trials=0: trials = 0 is not allowed: an integer from 1 to 100000"},
        {render + "tc7-phase --set qs=[0.5,1.5]",
         "--set qs=[0.5,1.5]: qs = [ 0.5, 1.5 ] is not allowed: [first, last, step] with 0 <= first <= last <= 1 and 0 "
         "< step <= 1, at most 10000 values"},
        {render + "tc7-phase --set walk_step=-1",
         "--set walk_step=-1: walk_step = -1 is not allowed: a number from 1e-06 to 0.5"},
        {render + "pc-threshold --set sizes=[64,32]",
         "--set sizes=[64,32]: sizes = [ 64, 32 ] is not allowed: 2 to 16 lattice sizes (two at least, to "
         "extrapolate), ascending, each an integer from 2 to 4096"},
        {render + "pc-threshold --set samples=1",
         "--set samples=1: samples = 1 is not allowed: an integer from 2 to 100000000"},
        {render + "pc-threshold --set criterion=\\\"sideways\\\"",
         "--set criterion=\"sideways\": criterion = 'sideways' is not allowed: \"one_direction\", \"either_direction\" "
         "or \"both_directions\""},
        {render + "pc-threshold --set samples=100000000 --set samples_per_item=1",
         "samples_per_item = 1 is not allowed: an integer from 1 to 1000000 giving at most 1000000 work items (4 sizes "
         "x samples / samples_per_item; it would give 400000000)"},
        // cellular automata
        {render + "tc7-6 --set rules=[256]", "--set rules=[256]: rules = 256 is not allowed: an integer from 0 to 255"},
        {render + "tc7-6 --set width=200001",
         "--set width=200001: width = 200001 is not allowed: each automaton at most 16384 cells a side (it would be 32 "
         "x 200001): the renderer draws one field that large"},
        {render + "tc7-7 --set rules=[-1]", "--set rules=[-1]: rules = -1 is not allowed: an integer from 0 to 255"},
        {render + "tc7-ex1 --set fit_from=100000",
         "--set fit_from=100000: fit_from = 100000 is not allowed: an integer from 1 to 498"},
        {render + "tc7-ex1 --set tolerance=-1",
         "--set tolerance=-1: tolerance = -1 is not allowed: a number from 0 to 0.5"},
        // forest fire
        {render + "tc7-ex2 --set p=2", "--set p=2: p = 2 is not allowed: a number from 0 to 1"},
        {render + "tc7-ex2 --set initial_density=1.5",
         "--set initial_density=1.5: initial_density = 1.5 is not allowed: a number from 0 to 1"},
        {render + "tc7-ex2 --set n=1", "--set n=1: n = 1 is not allowed: an integer from 3 to 8192"},
        // snowflakes
        {render + "sf87-3 --set runs=[]", "--set runs=[]: runs = [] is not allowed: one run at least"},
        {render + "sf87-dim --set runs=[]", "--set runs=[]: runs = [] is not allowed: one run at least"},
        {render + "pl-lsys-gallery --set plants=[]", "--set plants=[]: plants = [] is not allowed: one plant at least"},
        {render + "tc7-1 --set figure.panels=[3,3]",
         "figure.panels = [ 3, 3 ] is not allowed: steps from 0 to 100000000, ascending, each once"},
        {render + "sf87-3 --set rule=12345678",
         "rule = \"12345678\" is not allowed: a rule code is 7 binary digits d0..d6"},
        {render + "sf87-3 --set rule=\\\"01x1000\\\"",
         "rule = \"01x1000\" is not allowed: a rule code is 7 binary digits d0..d6"},
        {render + "sf87-4 --set steps=-3", "--set steps=-3: steps = -3 is not allowed: an integer from 0 to 4000"},
        {render + "sf87-5 --set restrict_radius=-1",
         "--set restrict_radius=-1: restrict_radius = -1 is not allowed: an integer from 1 to 1000000000"},
        {render + "sf87-6 --set priority_width=-2",
         "--set priority_width=-2: priority_width = -2 is not allowed: an integer from 0 to 1000000"},
        {render + "sf87-dim --set fit_to=100000",
         "--set fit_to=100000: fit_to = 100000 is not allowed: a number from 0.05 to 1"},
        {render + "sf87-2 --set row_cells=0",
         "--set row_cells=0: row_cells = 0 is not allowed: an odd number from 3 to 41"},
        // plants
        {render + "pl-phyllotaxis --set seeds=-10",
         "--set seeds=-10: seeds = -10 is not allowed: an integer from 1 to 50000"},
        {render + "pl-phyllotaxis --set divergences=[400]",
         "--set divergences=[400]: divergences[0] = 400 is not allowed: a number from 1e-09 to 360"},
        {render + "pl-ifs-fern --set discard=-5",
         "--set discard=-5: discard = -5 is not allowed: an integer from 0 to 100000000"},
        {render + "pl-ifs-tree --set bounds=[1,2]",
         "--set bounds=[1,2]: bounds = [1, 2] is not allowed: [xmin, xmax, ymin, ymax] with xmin < xmax and ymin < "
         "ymax, each from -1e+300 to 1e+300"},
        {render + "pl-lsys-lycopodium --set depth=-1",
         "--set depth=-1: depth = -1 is not allowed: an integer from 0 to 64"},
        {render + "pl-lsys-apple --set angle=nan",
         "--set angle=nan: angle = nan is not allowed: expected a finite number"},
        {render + "pl-lsys-gallery --set plus=\\\"up\\\"",
         "--set plus=\"up\": plus = 'up' is not allowed: \"left\" or \"right\""},
        {render + "pl-lsys-3d --set width_decay=-1",
         "--set width_decay=-1: width_decay = -1 is not allowed: a finite number above 0"},
        // Settings of the drawing, checked before the model runs like the model's own.
        {render + "pl-lsys-3d --set style.sides=0",
         "--set style.sides=0: style.sides = 0 is not allowed: an integer from 3 to 256"},
        {render + "pl-lsys-3d --set style.leaf_index=0",
         "--set style.leaf_index=0: style.leaf_index = 0 is not allowed: an integer from 1 to 1048576"},
        // Polygons: a '{' never closed, a '}' that closes nothing, and more vertices than the turtle's budget.
        {render + "pl-lsys-3d --set 'rules=[\"A -> F{-f+f+f\"]'",
         "rules[0] = \"A -> F{-f+f+f\" is not allowed: balanced braces, every '{' (a polygon begins) with a later '}' "
         "(it ends)"},
        {render + "pl-lsys-3d --set 'rules=[\"A -> F}-f{\"]'",
         "rules[0] = \"A -> F}-f{\" is not allowed: balanced braces"},
        {render + "pl-lsys-3d --set axiom=FX --set 'rules=[\"X -> {ffff}XX\"]' --set depth=20",
         "depth = 20 is not allowed: a depth within the turtle's budget (its polygons would have 5,242,875 vertices, "
         "more than the budget of 5,000,000)"},
        {render + "tc7-phase --set p_c=1e308", "--set p_c=1e308: p_c = 1e+308 is not allowed: "},
        {render + "pl-lsys-gallery --set 'plants=[{axiom=\"F\", angle=1e308}]'",
         "plants[0].angle = 1e+308 is not allowed: a number from -1e+300 to 1e+300"},
        // The arrowhead, drawing with A and B, not with the default F.
        {render + "pl-lsys-lycopodium --set axiom=A --set 'rules=[\"A -> B-A-B\", \"B -> A+B+A\"]' --set depth=4",
         "draw = \"F\" is not allowed: symbols its string has, which draw a step: it has AB (e.g. draw = \"AB\""},
        {render + "pl-lsys-lycopodium --set draw=F+",
         "--set draw=F+: draw = \"F+\" is not allowed: letters and other printable symbols, each once, none of the "
         "turtle's commands"},
        {render + "pl-lsys-lycopodium --set move=F",
         "move = \"F\" is not allowed: letters and other printable symbols, each once,"},
        {render + "tc7-7 --set style.line_width=-1",
         "--set style.line_width=-1: style.line_width = -1 is not allowed: a number from 0.1 to 50"},
        {render + "tc7-9 --set style.font_size=1000", "style.font_size = 1000 is not allowed: a number from 4 to 100"},
        {render + "tc7-2 --set style.a_alpha=2", "style.a_alpha = 2 is not allowed: a number from 0 to 1"},
        {render + "tc7-ex2 --set style.trees_colour=\\\"chartreuse-ish\\\"",
         "style.trees_colour = 'chartreuse-ish' is not allowed: #rrggbb or one of "},
        // titles and captions that would overlap
        {render + "sf87-3 --size 333x111",
         "figure.size = [333, 111] is not allowed: a size at which the figure's text fits: at 333 x 111 pixels the "
         "title of panel 1 "},
        {render + "pl-lsys-gallery --size 300x300",
         "figure.size = [300, 300] is not allowed: a size at which the figure's text fits: "},
        // The plots' own text: tick labels, legends, colour bars.
        {render + "tc7-7 --size 333x111",
         "figure.size = [333, 111] is not allowed: a size at which the figure's text fits: at 333 x 111 pixels the y "
         "axis label of plot 1 [18, -19, 12 x 127] runs off the page; [628, 210] or larger holds them"},
        {render + "tc7-9 --size 300x200",
         "figure.size = [300, 200] is not allowed: a size at which the figure's text fits: at 300 x 200 pixels the "
         "legend [114, 52, 127 x 99] runs out of the frame of the plot; [331, 221] or larger"},
        {render + "bd-500 --size 333x111 --set particles=5000 --set width=100",
         "figure.size = [333, 111] is not allowed: a size at which the figure's text fits: at 333 x 111 pixels the "
         "colour bar's label of panel 1 [203, -19, 14 x 178] runs off the page"},
        {render + "pl-lsys-3d --size 200x100",
         "at 200 x 100 pixels the title of panel 2 [92, 20, 113 x 14] runs off the page; [232, 116] or larger holds "
         "them (or set fewer style.views)"},
        {render + "sf87-2 --size 333x111",
         "at 333 x 111 pixels the label i−1 of (a) [52, 29, 26 x 12] runs out of its cell; [570, 190] or larger holds "
         "them"},
        {render + "gs-atlas --size 333x111",
         "at 333 x 111 pixels the title [-28, 8, 379 x 15] runs off the page; [1440, 480] or larger holds them"},
        {render + "tc7-1 --set figure.columns=0", "figure.columns = 0 is not allowed: an integer from 1 to 64"},
        // captions beneath the figure
        {render + "tc7-1 --set figure.caption=original",
         "figure.caption = \"original\" is not allowed: \"none\" or \"title\": the description has no "
         "original_caption"},
        {render + "sf87-3 --set figure.caption=below",
         "figure.caption = \"below\" is not allowed: \"none\", \"title\" or \"original\""},
        {render + "sf87-3 --set figure.caption=original --size 200x40",
         "figure.caption = \"original\" at 200 x 40 is not allowed: a figure whose caption fits in a third of its "
         "height: its 2 line(s) take 51 px; --size 200x153 or larger fits them"},
        {render + description("lang.toml", head + "language = \"Chinese\"\n"),
         "lang.toml:3: language = \"Chinese\" is not allowed: a language tag of lower-case letters"},
        {render +
             description("lang2.toml",
                         head + "language = \"xq-zz\"\noriginal_caption = \"x\"\n[figure]\ncaption = \"original\"\n"),
         "lang2.toml:3: language = \"xq-zz\" is not allowed: a language fontconfig knows"},
        // ballistic deposition
        {render + "bd-500 --set width=0", "--set width=0: width = 0 is not allowed: an integer from 3 to 10000000"},
        {render + "bd-500 --set particles=50000000 --set width=3",
         "--set particles=50000000: particles = 50000000 is not allowed: the deposit's view at most 16384 cells a side "
         "(it would be 40000016 x 3): the renderer draws one field that large"},
        {render + "bd-roughness --set seeds=0", "--set seeds=0: seeds = 0 is not allowed: an integer from 1 to 1000"},
        {render + "bd-roughness --set beta_range=[50,2]",
         "--set beta_range=[50,2]: beta_range = [ 50, 2 ] is not allowed: [t1, t2] with 0 < t1 < t2"},
        // Description files: syntax, types and keys name the file and line.
        {render + description("syntax.toml", head + "[params\nn = 3\n"), "syntax.toml:3: "},
        {render + description("type.toml", head + "[params]\nn = 3\nr = \"fast\"\n"),
         "type.toml:5: r = 'fast' is not allowed: expected a number"},
        {render + description("key.toml", head + "\n[params]\nrate = 0.1\n"),
         "key.toml:5: unknown key params.rate; allowed: n, r, boundary"},
        {render + description("range.toml", head + "[params]\nr = 0.9\n"),
         "range.toml:4: r = 0.9 is not allowed: a number from 0 to 0.25 (the explicit 5-point update's stability "
         "bound; beyond it the checkerboard grows)"},
        {render + description("size.toml", head + "[figure]\npanels = [0]\nsize = \"big\"\n"),
         "size.toml:5: figure.size = 'big' is not allowed: expected a list of integers"},
        {render + description("top.toml", head + "colour = \"red\"\n"),
         "top.toml:3: unknown key description.colour; allowed: id, title"},
        {render + description("nomodel.toml", "id = \"x\"\n"),
         "nomodel.toml: scene is missing: give a scene name, e.g. scene = \"gray_scott\""},
        {render + description("model.toml", "id = \"x\"\nmodel = \"lava-lamp\"\n"),
         "model.toml:2: scene = \"lava-lamp\" is not allowed: one of diffusion, "},
        {render + description("seed.toml", head + "seed = -4\n"),
         "seed.toml:3: seed = -4 is not allowed: an integer from 0 to 2^63-1"},
    };
    STATIC_REQUIRE(sizeof cases / sizeof cases[0] >= 60);
    for (const Case& c : cases) {
        INFO("figgen " << c.args);
        const Run run = figgen(c.args);
        CHECK(run.status == 2);
        CHECK(run.lines() == 1);
        CHECK_THAT(run.output, Catch::StartsWith("figgen: error: ") && Catch::Contains(c.expected));
    }
    CHECK(folder_contents(out) == before);  // nothing written or changed, not even a temporary
}

TEST_CASE("a bad setting found in phase 1 creates nothing, not even the output folder", "[cli]") {
    const fs::path parent = fresh_dir("phase1");
    const fs::path out = parent / "never-made";
    // The last two: text that does not fit, found before any model runs (the atlas's axes and the schematic).
    for (const std::string set : {"style.sides=0 pl-lsys-3d", "p_c=1e308 tc7-phase", "n=64 gs-atlas --size 333x111",
                                  "radius=2 sf87-2 --size 333x111"}) {
        INFO(set);
        const Run run = figgen("render --out " + out.string() + " --set " + set);
        CHECK(run.status == 2);
        CHECK(run.lines() == 1);
        CHECK_FALSE(fs::exists(out));
    }
    CHECK(fs::is_empty(parent));
}

TEST_CASE("a refused input is said by every process that has no rank 0 to say it", "[cli][cluster]") {
    const fs::path out = fresh_dir("faked-mpi") / "never-made";
    // Rank 1 of a real launch (PMIx's namespace and rank agreeing): rank 0 says it, this rank keeps quiet.
    const Run launched = testkit::figgen_env("OMPI_COMM_WORLD_SIZE=4 OMPI_COMM_WORLD_RANK=1 PMIX_RANK=1 PMIX_NAMESPACE=job7",
                                             "render no-such-figure --out " + out.string());
    CHECK(launched.status == 2);
    CHECK(launched.output.empty());
    // Open MPI's variables alone, or a PMIx rank that disagrees: no launcher around it, so it says it itself.
    for (const std::string env : {"OMPI_COMM_WORLD_SIZE=4 OMPI_COMM_WORLD_RANK=1",
                                  "OMPI_COMM_WORLD_SIZE=4 OMPI_COMM_WORLD_RANK=1 PMIX_RANK=2 PMIX_NAMESPACE=job7"}) {
        INFO(env);
        const Run faked = testkit::figgen_env(env, "render no-such-figure --out " + out.string());
        CHECK(faked.status == 2);
        CHECK(faked.lines() == 1);
        CHECK(faked.output.find("figgen: error: unknown figure id 'no-such-figure'") == 0);
    }
    CHECK_FALSE(fs::exists(out));
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
    CHECK_THAT(unknown.output, Catch::Contains("unknown-model.toml:2: scene = \"lava-lamp\" is not allowed: one of diffusion, "));
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

    const auto png = media::read_png(out / "tc7-1.png");
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
    const auto last = media::read_png(out / "tc7-1-frames" / "00009.png");
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
    const auto info = media::probe_video(out / "tc7-1.mp4");
    CHECK(info.frames == 61);  // steps 0..60
    CHECK(info.width == 240);
    CHECK(info.height == 260);
    CHECK(info.pixel_format == "yuv420p");
    CHECK(info.codec == "h264");
    CHECK(info.duration_seconds == Approx(6.1).margin(1e-6));  // 61 frames at 10 fps
    // The first frame is step 0: the block's centre is Reds' darkest colour
    // at alpha 0.8 over white, (133, 51, 61), give or take the YUV round trip.
    const render::Image first = media::decode_frame(out / "tc7-1.mp4", 0);
    const std::uint8_t* centre = first.pixel(first.width / 2, first.height / 2 + 10);
    CHECK(int(centre[0]) == Approx(133).margin(8));
    CHECK(int(centre[1]) == Approx(51).margin(8));
    CHECK(int(centre[2]) == Approx(61).margin(8));
}

TEST_CASE("a film comes with a looping WebP preview that its JSON describes, the same bytes every run", "[cli][preview]") {
    const fs::path out = fresh_dir("preview"), again = fresh_dir("preview-again");
    REQUIRE(figgen("render tc7-1 --scale 0.5 --out " + out.string()).status == 0);
    const media::PreviewInfo preview = media::probe_preview(out / "tc7-1.webp");
    std::ifstream in(out / "tc7-1.json");
    const nlohmann::json meta = nlohmann::json::parse(in)["animation"]["preview"];
    CHECK(meta["file"] == "tc7-1.webp");
    // 61 frames of 240 x 260: 48 of them, fitted into 360 x 360 (not enlarged),
    // over the film's 6.1 s capped at 4 s: 48 x 83 ms.
    CHECK(preview.frames == 48);
    CHECK(preview.width == 240);
    CHECK(preview.height == 260);
    CHECK(preview.loop_count == 0);
    CHECK(preview.duration_ms == 48 * 83);
    CHECK(meta["frames"] == preview.frames);
    CHECK(meta["size"] == nlohmann::json::array({preview.width, preview.height}));
    CHECK(meta["duration_ms"] == preview.duration_ms);
    CHECK(preview.bytes <= media::PreviewOptions{}.max_bytes);
    // Its last frame is the film's: the same colours but for lossy coding.
    const render::Image last = media::decode_preview_frame(out / "tc7-1.webp", 47);
    // Mean difference a channel: lossy WebP after H.264 leaves about 5;
    // the film's first frame, against which it is checked too, more than twice that.
    const auto mean_difference = [&](const render::Image& film) {
        double differ = 0;
        for (std::size_t i = 0; i < last.rgba.size(); ++i) differ += std::abs(int(last.rgba[i]) - int(film.rgba[i]));
        return differ / double(last.rgba.size());
    };
    const double to_last = mean_difference(media::decode_frame(out / "tc7-1.mp4", 60));
    const double to_first = mean_difference(media::decode_frame(out / "tc7-1.mp4", 0));
    CHECK(to_last < 8.0);
    CHECK(to_first > 2 * to_last);
    REQUIRE(figgen("render tc7-1 --scale 0.5 --out " + again.string()).status == 0);
    CHECK(testkit::slurp(again / "tc7-1.webp") == testkit::slurp(out / "tc7-1.webp"));
}

TEST_CASE("render --format webm writes VP9 in WebM that decodes to every frame, the same bytes every run",
          "[cli][webm]") {
    std::string first;
    for (int run = 0; run < 2; ++run) {
        const fs::path out = fresh_dir("webm-" + std::to_string(run));
        const Run r = figgen("render tc7-1 --scale 0.3 --format mp4,webm --out " + out.string());
        INFO(r.output);
        REQUIRE(r.status == 0);
        std::ifstream in(out / "tc7-1.json");
        const nlohmann::json film = nlohmann::json::parse(in)["animation"];
        const media::VideoInfo mp4 = media::probe_video(out / "tc7-1.mp4");
        const media::VideoInfo webm = media::probe_video(out / "tc7-1.webm");
        CHECK(webm.codec == "vp9");
        CHECK(webm.frames == film["frames"].get<int>());
        CHECK(webm.frames == mp4.frames);
        CHECK(webm.width == mp4.width);
        CHECK(webm.height == mp4.height);
        CHECK(std::abs(webm.fps - mp4.fps) < 1e-6);
        CHECK(film["webm"]["file"] == "tc7-1.webm");
        CHECK(film["webm"]["bytes"].get<std::uintmax_t>() == fs::file_size(out / "tc7-1.webm"));
        // Its last frame is the film's last frame, but for the two lossy codecs.
        const render::Image a = media::decode_frame(out / "tc7-1.mp4", mp4.frames - 1);
        const render::Image b = media::decode_frame(out / "tc7-1.webm", webm.frames - 1);
        double difference = 0;
        for (std::size_t i = 0; i < a.rgba.size(); ++i) difference += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
        CHECK(difference / double(a.rgba.size()) < 3.0);
        const std::string bytes = testkit::slurp(out / "tc7-1.webm");
        if (run == 0) first = bytes;
        else CHECK(bytes == first);
    }
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

TEST_CASE("plants whose numbers overflow stop with an error naming the point or segment and write nothing", "[cli]") {
    const fs::path out = fresh_dir("unstable-plants");
    struct Case {
        std::string args;
        std::string expected;
    };
    const Case cases[] = {
        // Maps that double and triple: 4096 points reach 2^4096, far beyond 1e100.
        {"pl-ifs-tree --set variants=[{maps=[[2,0,0,2,0,0,0.5],[3,0,0,3,1,0,0.5]]}]",
         "the chaos game went numerically unstable at point 4096 (a coordinate beyond 1e100: the maps do not contract)"},
        // A first step of 1e300 from the origin, a second from there: 2e300.
        {"pl-lsys-apple --set length=1e300", "the turtle went numerically unstable at segment 2 of 340"},
        {"pl-lsys-3d --set length=1e300", "the turtle went numerically unstable at segment 2 of 3891"},
    };
    for (const Case& c : cases) {
        INFO(c.args);
        const Run run = figgen("render --out " + out.string() + " " + c.args);
        CHECK(run.status == 1);
        CHECK(run.lines() == 1);
        CHECK_THAT(run.output, Catch::StartsWith("figgen: error: ") && Catch::Contains(c.expected) &&
                                   Catch::EndsWith("no image written\n"));
    }
    CHECK(fs::is_empty(out));
}

namespace {

std::vector<std::string> files_in(const fs::path& dir) {
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());
    return files;
}

nlohmann::json metadata(const fs::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("render --size sets the figure's pixels before --scale", "[cli][options]") {
    const fs::path out = fresh_dir("size");
    REQUIRE(figgen("render tc7-1 --format png --size 300x200 --out " + out.string()).status == 0);
    const auto png = media::read_png(out / "tc7-1.png").image;
    CHECK(png.width == 300);
    CHECK(png.height == 200);
    REQUIRE(figgen("render tc7-1 --format png --size 300x200 --scale 2 --out " + out.string()).status == 0);
    CHECK(media::read_png(out / "tc7-1.png").image.width == 600);
    CHECK(metadata(out / "tc7-1.json")["image"]["size"] == nlohmann::json({600, 400}));
}

TEST_CASE("a plot whose text does not fit is refused with a size at which it renders", "[cli][options]") {
    const fs::path out = fresh_dir("plot-fit");
    for (const char* id : {"tc7-7", "tc7-9", "sf87-dim"}) {
        INFO(id);
        const Run refused = figgen(std::string("render ") + id + " --format png --size 300x150 --out " + out.string());
        REQUIRE(refused.status == 2);
        CHECK(fs::is_empty(out));
        // "...; [W, H] or larger holds them"
        const std::size_t end = refused.output.find("] or larger holds them");
        REQUIRE(end != std::string::npos);
        const std::size_t start = refused.output.rfind('[', end);
        int w = 0, h = 0;
        REQUIRE(std::sscanf(refused.output.c_str() + start, "[%d, %d]", &w, &h) == 2);
        CHECK(w > 300);
        CHECK(h * 300 == Approx(w * 150).margin(300));  // the aspect asked for
        REQUIRE(figgen(std::string("render ") + id + " --format png --size " + std::to_string(w) + "x" +
                       std::to_string(h) + " --out " + out.string())
                    .status == 0);
        CHECK(media::read_png(out / (std::string(id) + ".png")).image.width == w);
        fs::remove_all(out);
        fs::create_directories(out);
    }
}

TEST_CASE("a figure is the exact size asked for and only its film rounds to even as its JSON says", "[cli][options]") {
    const fs::path out = fresh_dir("exact-size");
    // The snowflakes' captions, a label each: their whole sentences do not fit beside each other at 333 px.
    // The plots' text at half its size (a 50 dpi figure): at 100 dpi their tick labels crowd at 111 px.
    for (const char* id : {"tc7-7", "sf87-3", "pl-lsys-lycopodium"}) {
        INFO(id);
        const std::string extra = std::string(id) == "sf87-3"  ? " --set style.caption={label}"
                                  : std::string(id) == "tc7-7" ? " --set style.plot_scale=0.5"
                                                               : "";
        REQUIRE(figgen(std::string("render ") + id + extra + " --format png,pdf --size 333x111 --out " + out.string())
                    .status == 0);
        const auto png = media::read_png(out / (std::string(id) + ".png")).image;
        CHECK(png.width == 333);
        CHECK(png.height == 111);
        CHECK(metadata(out / (std::string(id) + ".json"))["image"]["size"] == nlohmann::json({333, 111}));
    }
    // 0.5 of 900 x 450 is 450 x 225, not 226.
    REQUIRE(figgen("render tc7-1 --scale 0.5 --set 'animation.size=[333,111]' --out " + out.string()).status == 0);
    CHECK(media::read_png(out / "tc7-1.png").image.height == 225);
    const nlohmann::json film = metadata(out / "tc7-1.json")["animation"];
    CHECK(film["size"] == nlohmann::json({168, 56}));  // 166.5 x 55.5 rounds to 167 x 56, then up to even
    CHECK(film["size_rounded"]["from"] == nlohmann::json({167, 56}));
    const media::VideoInfo mp4 = media::probe_video(out / "tc7-1.mp4");
    CHECK(mp4.width == 168);
    CHECK(mp4.height == 56);
    // An even film says nothing.
    REQUIRE(figgen("render tc7-1 --scale 0.3 --out " + out.string()).status == 0);
    CHECK_FALSE(metadata(out / "tc7-1.json")["animation"].contains("size_rounded"));
}

TEST_CASE("render --fps sets the animation's frame rate in the MP4 and its metadata", "[cli][options]") {
    const fs::path out = fresh_dir("fps");
    REQUIRE(figgen("render tc7-1 --fps 5 --scale 0.5 --out " + out.string()).status == 0);
    const auto meta = metadata(out / "tc7-1.json");
    CHECK(meta["animation"]["fps"] == 5);
    const media::VideoInfo video = media::probe_video(out / "tc7-1.mp4");
    CHECK(video.fps == Approx(5.0));
    CHECK(video.frames == meta["animation"]["frames"].get<int>());
    CHECK(video.duration_seconds == Approx(video.frames / 5.0).margin(0.21));
}

TEST_CASE("render --cmap recolours a field figure with matplotlib's colormap", "[cli][options]") {
    const fs::path out = fresh_dir("cmap");
    // tc7-1 at step 0 is a block of 1 on 0, drawn with vmin 0, vmax 1 at
    // alpha 0.8 over white: the background is 0.8 * cmap(0) + 0.2 * white.
    for (const auto& [name, first] : std::vector<std::pair<std::string, std::array<double, 3>>>{
             {"inferno", {0.001462, 0.000466, 0.013866}},  // matplotlib's _inferno_data[0]
             {"cividis", {0.0, 0.135112, 0.304751}},       // _cividis_data[0]
         }) {
        INFO(name);
        REQUIRE(figgen("render tc7-1 --format png --cmap " + name + " --out " + out.string()).status == 0);
        const auto meta = metadata(out / "tc7-1.json");
        CHECK(meta["style"]["colormap"] == name);
        const auto png = media::read_png(out / "tc7-1.png").image;
        // A background cell of the first panel: its frame starts a little way
        // in; take a pixel well inside the first panel, away from the block.
        const auto* p = png.pixel(png.width / 12, png.height / 2);
        for (int c = 0; c < 3; ++c) CHECK(std::abs(p[c] - 255.0 * (0.8 * first[c] + 0.2)) <= 2.0);
    }
    // Gray-Scott's two fields both take it; a list of colours gives way to it.
    REQUIRE(figgen("render tc7-2 tc7-ex2 --format png --scale 0.3 --cmap magma --out " + out.string()).status == 0);
    CHECK(metadata(out / "tc7-2.json")["style"]["a_colormap"] == "magma");
    CHECK(metadata(out / "tc7-2.json")["style"]["b_colormap"] == "magma");
    CHECK(metadata(out / "tc7-ex2.json")["style"]["colormap"] == "magma");
    CHECK_FALSE(metadata(out / "tc7-ex2.json")["style"].contains("colours"));
    // A formula figure's chemicals (its rule's alone) and an atlas take it;
    // their colours and how those were blended give way.
    const Run formula = figgen("render fx-brusselator --format png --scale 0.3 --set steps=50 "
                               "--set figure.panels=[0,50] --cmap magma --out " + out.string());
    INFO(formula.output);
    REQUIRE(formula.status == 0);
    const Run atlas = figgen("render fx-pearson-map --format png --scale 0.3 --set tiles=[2,2] --set steps=50 "
                             "--cmap magma --out " + out.string());
    INFO(atlas.output);
    REQUIRE(atlas.status == 0);
    const auto brusselator = metadata(out / "fx-brusselator.json")["style"];
    CHECK(brusselator["b_colormap"] == "magma");
    CHECK_FALSE(brusselator.contains("b_colours"));
    CHECK_FALSE(brusselator.contains("b_blend"));
    CHECK(metadata(out / "fx-pearson-map.json")["style"]["colormap"] == "magma");
}

TEST_CASE("render --format, a list of png, pdf, svg, mp4 and frames, chooses what is written besides the PNG",
          "[cli][options]") {
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {"png", {"tc7-1.json", "tc7-1.png"}},
        {"mp4", {"tc7-1.json", "tc7-1.mp4", "tc7-1.png", "tc7-1.webp"}},  // the film and its preview
        {"frames", {"tc7-1-frames", "tc7-1.json", "tc7-1.png"}},
        {"pdf", {"tc7-1.json", "tc7-1.pdf", "tc7-1.png"}},
        {"png,svg", {"tc7-1.json", "tc7-1.png", "tc7-1.svg"}},
        {"png,pdf,mp4", {"tc7-1.json", "tc7-1.mp4", "tc7-1.pdf", "tc7-1.png", "tc7-1.webp"}},
        {"svg,frames,pdf", {"tc7-1-frames", "tc7-1.json", "tc7-1.pdf", "tc7-1.png", "tc7-1.svg"}},
        {"webm", {"tc7-1.json", "tc7-1.png", "tc7-1.webm", "tc7-1.webp"}},  // the MP4 it is made from is dropped
        {"mp4,webm", {"tc7-1.json", "tc7-1.mp4", "tc7-1.png", "tc7-1.webm", "tc7-1.webp"}},
    };
    for (const auto& [format, expected] : cases) {
        INFO(format);
        const fs::path out = fresh_dir("format-" + format);
        REQUIRE(figgen("render tc7-1 --scale 0.3 --format " + format + " --out " + out.string()).status == 0);
        CHECK(files_in(out) == expected);
    }
}

TEST_CASE("figgen --version prints the version", "[cli][options]") {
    const Run run = figgen("--version");
    CHECK(run.status == 0);
    CHECK_THAT(run.output, Catch::Matches("[0-9]+\\.[0-9]+\\.[0-9]+\\s*"));
}

TEST_CASE("only a command that draws opens the GL library", "[cli][gl]") {
    // glibc's loader names every library it opens under LD_DEBUG=files.
    struct Opened {
        bool osmesa, egl, llvm;
    };
    auto opened = [](const std::string& args) {
        const Run run = testkit::figgen_env("LD_DEBUG=files", args);
        return Opened{run.output.find("file=libOSMesa.so") != std::string::npos,
                      run.output.find("file=libEGL.so") != std::string::npos,
                      run.output.find("file=libLLVM") != std::string::npos};
    };
    auto opens_gl = [&](const std::string& args) {
        const Opened o = opened(args);
        return o.osmesa || o.egl || o.llvm;
    };
    const fs::path out = fresh_dir("gl-loading");
    CHECK_FALSE(opens_gl("--version"));
    CHECK_FALSE(opens_gl("list"));
    CHECK_FALSE(opens_gl("describe tc7-1"));
    CHECK_FALSE(opens_gl("render tc7-1 --scale 9 --out " + out.string()));     // a refused option
    CHECK_FALSE(opens_gl("render tc7-1 --set n=-3 --out " + out.string()));    // a refused setting
    CHECK_FALSE(opens_gl("render tc7-6 --set width=20001 --out " + out.string()));  // a field too large to draw
    CHECK_FALSE(opens_gl("render tc7-1 --gl egl --gl-device 1 --out " + out.string()));  // a refused --gl
    // One that draws opens the library its --gl names, and only that one
    // (auto: EGL, which works here, so OSMesa is never opened).
    const Opened automatic = opened("render tc7-7 --format png --out " + out.string());
    CHECK(automatic.egl);
    CHECK_FALSE(automatic.osmesa);
    CHECK(automatic.llvm);
    const Opened osmesa = opened("render tc7-7 --format png --gl osmesa --out " + out.string());
    CHECK(osmesa.osmesa);
    CHECK_FALSE(osmesa.egl);
}

TEST_CASE("a description's figure.formats asks for its vector files, and --format decides instead", "[cli][options]") {
    const fs::path files = fresh_dir("formats-description");
    std::ofstream(files / "mine.toml") << "id = \"mine\"\nscene = \"diffusion\"\n[params]\nn = 16\n"
                                          "[figure]\npanels = [0, 5]\nformats = [\"png\", \"svg\", \"pdf\"]\n";
    const fs::path out = fresh_dir("formats-asked");
    const Run asked = figgen("render " + (files / "mine.toml").string() + " --out " + out.string());
    INFO(asked.output);
    REQUIRE(asked.status == 0);
    CHECK(files_in(out) == std::vector<std::string>{"mine.json", "mine.pdf", "mine.png", "mine.svg"});
    std::ifstream in(out / "mine.json");
    const nlohmann::json meta = nlohmann::json::parse(in);
    CHECK(meta["vector"]["pdf"]["file"] == "mine.pdf");
    CHECK(meta["vector"]["svg"]["bytes"].get<double>() == double(fs::file_size(out / "mine.svg")));
    const fs::path decided = fresh_dir("formats-decided");
    REQUIRE(figgen("render " + (files / "mine.toml").string() + " --format png --out " + decided.string()).status ==
            0);
    CHECK(files_in(decided) == std::vector<std::string>{"mine.json", "mine.png"});
}

TEST_CASE("a new user's Sierpinski gasket and arrowhead draw with their own symbols", "[cli][lsystem]") {
    const fs::path files = fresh_dir("gasket");
    std::ofstream(files / "sierpinski.toml")
        << "id = \"sierpinski\"\nscene = \"lsystem\"\n[params]\nplus = \"left\"\nlength = 10\n"
           "[[params.plants]]\ntitle = \"gasket\"\naxiom = \"F-G-G\"\nrules = [\"F -> F-G+F+G-F\", \"G -> GG\"]\n"
           "angle = 120\ndepth = 5\ndraw = \"FG\"\n"
           "[[params.plants]]\ntitle = \"arrowhead\"\naxiom = \"A\"\nrules = [\"A -> B-A-B\", \"B -> A+B+A\"]\n"
           "angle = 60\ndepth = 6\ndraw = \"AB\"\n[figure]\nsize = [800, 400]\n";
    const fs::path out = fresh_dir("gasket-out");
    const Run run = figgen("render " + (files / "sierpinski.toml").string() + " --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    std::ifstream in(out / "sierpinski.json");
    const nlohmann::json panels = nlohmann::json::parse(in)["panels"];
    CHECK(panels[0]["segments"] == 729);  // 3^(5+1)
    CHECK(panels[1]["segments"] == 729);  // 3^6
    CHECK(panels[0]["plant"]["draw"] == "FG");
}

TEST_CASE("IFS panels show their own points' bounds unless the description asks for shared ones", "[cli][ifs]") {
    // A Sierpinski triangle, and the same triangle ten times larger and moved.
    const fs::path files = fresh_dir("ifs-bounds");
    std::ofstream(files / "triangles.toml")
        << "id = \"triangles\"\nscene = \"ifs\"\n[params]\npoints = 20000\n"
           "[[params.variants]]\ntitle = \"small\"\n"
           "maps = [[0.5, 0, 0, 0.5, 0, 0, 0.34], [0.5, 0, 0, 0.5, 0.5, 0, 0.33], [0.5, 0, 0, 0.5, 0.25, 0.5, 0.33]]\n"
           "[[params.variants]]\ntitle = \"large\"\n"
           "maps = [[0.5, 0, 0, 0.5, 20, 0, 0.34], [0.5, 0, 0, 0.5, 25, 0, 0.33], [0.5, 0, 0, 0.5, 22.5, 5, 0.33]]\n";
    for (const bool shared : {false, true}) {
        INFO("shared_bounds = " << shared);
        const fs::path out = fresh_dir(shared ? "ifs-shared" : "ifs-own");
        const Run run = figgen("render " + (files / "triangles.toml").string() + " --format png --out " +
                               out.string() + (shared ? " --set shared_bounds=true" : ""));
        INFO(run.output);
        REQUIRE(run.status == 0);
        std::ifstream in(out / "triangles.json");
        const nlohmann::json panels = nlohmann::json::parse(in)["panels"];
        auto extent = [](const nlohmann::json& box, int axis) {
            return box[2 * axis + 1].get<double>() - box[2 * axis].get<double>();
        };
        for (const auto& p : panels) {
            const auto& own = p["points_bounds"];
            const auto& drawn = p["drawn_bounds"];
            CHECK(drawn[0].get<double>() <= own[0].get<double>());  // every point inside
            CHECK(drawn[1].get<double>() >= own[1].get<double>());
            CHECK(drawn[2].get<double>() <= own[2].get<double>());
            CHECK(drawn[3].get<double>() >= own[3].get<double>());
            // Own bounds: the cloud spans its box one way, widened only the other.
            if (!shared)
                CHECK(std::min(std::abs(extent(drawn, 0) - extent(own, 0)) / extent(drawn, 0),
                               std::abs(extent(drawn, 1) - extent(own, 1)) / extent(drawn, 1)) < 1e-9);
        }
        if (shared) {
            CHECK(panels[0]["drawn_bounds"] == panels[1]["drawn_bounds"]);
            // The small triangle then takes less than a twentieth of its panel's width.
            CHECK(extent(panels[0]["points_bounds"], 0) * 20 < extent(panels[0]["drawn_bounds"], 0));
        } else {
            CHECK(panels[0]["drawn_bounds"] != panels[1]["drawn_bounds"]);
        }
    }
}

TEST_CASE("render --transparent leaves the background out: alpha 0 at the corners, opaque ink", "[cli][options]") {
    const fs::path out = fresh_dir("transparent");
    const Run run = figgen("render tc7-7 --transparent --format png,svg --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    const render::Image png = media::read_png(out / "tc7-7.png").image;
    for (const auto& [x, y] : {std::pair{0, 0}, std::pair{png.width - 1, 0}, std::pair{0, png.height - 1},
                               std::pair{png.width - 1, png.height - 1}})
        CHECK(int(png.pixel(x, y)[3]) == 0);
    long opaque = 0, clear = 0;
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width; ++x) {
            opaque += png.pixel(x, y)[3] == 255;  // the lines, the legends' boxes
            clear += png.pixel(x, y)[3] == 0;
        }
    CHECK(opaque > 5000);
    CHECK(clear > png.width * png.height / 2);
    std::ifstream in(out / "tc7-7.json");
    CHECK(nlohmann::json::parse(in)["image"]["transparent"] == true);
    // The SVG likewise: librsvg's raster of it is clear at the corners.
    const Run svg = testkit::run_command("rsvg-convert '" + (out / "tc7-7.svg").string() + "' -o '" +
                                         (out / "svg.png").string() + "'");
    REQUIRE(svg.status == 0);
    const render::Image raster = media::read_png(out / "svg.png").image;
    CHECK(int(raster.pixel(0, 0)[3]) == 0);
    CHECK(int(raster.pixel(raster.width - 1, raster.height - 1)[3]) == 0);
}

TEST_CASE("the deposit's colour bar runs over its arrival times, its ticks labelled from 0 to the last monolayer",
          "[cli][colour-bar]") {
    const fs::path out = fresh_dir("colour-bar");
    // 40 columns, 1,600 particles in 20 bands of 80: 2 monolayers a band, 40 in all.
    const Run run = figgen("render bd-500 --set width=40 --set particles=1600 --format pdf --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    std::ifstream in(out / "bd-500.json");
    const nlohmann::json meta = nlohmann::json::parse(in);
    const nlohmann::json& bar = meta["colour_bar"];
    CHECK(bar["label"] == "arrival time (monolayers)");
    CHECK(bar["low"] == 0.0);
    CHECK(bar["high"] == 20.0 * meta["panels"][0]["band_particles"].get<double>() / 40.0);
    CHECK(bar["high"] == 40.0);
    CHECK(bar["entries"] == 20);
    // The labels as drawn: poppler reads them back from the PDF.
    const Run text = testkit::run_command("pdftotext -raw '" + (out / "bd-500.pdf").string() + "' -");
    REQUIRE(text.status == 0);
    for (const char* tick : {"\n0\n", "\n10\n", "\n20\n", "\n30\n", "\n40\n"}) CHECK(text.output.find(tick) != std::string::npos);
    CHECK(text.output.find("\n50\n") == std::string::npos);
    CHECK(text.output.find("arrival") != std::string::npos);
    // Off by its style key.
    const fs::path plain = fresh_dir("colour-bar-off");
    REQUIRE(figgen("render bd-500 --set width=40 --set particles=1600 --set style.colour_bar=false --format png "
                   "--out " + plain.string()).status == 0);
    std::ifstream plain_in(plain / "bd-500.json");
    CHECK_FALSE(nlohmann::json::parse(plain_in).contains("colour_bar"));
}

TEST_CASE("only a figure written as PDF or SVG opens cairo", "[cli][vector]") {
    auto opens_cairo = [](const std::string& args) {
        const Run run = testkit::figgen_env("LD_DEBUG=files", args);
        const bool module = run.output.find("file=" FIGGEN_BUILD_DIR "/lib/libfiggen_vector.so") != std::string::npos;
        const bool cairo = run.output.find("file=libcairo.so") != std::string::npos;
        CHECK(module == cairo);  // cairo comes only with the module
        return cairo;
    };
    const fs::path out = fresh_dir("vector-loading");
    CHECK_FALSE(opens_cairo("--version"));
    CHECK_FALSE(opens_cairo("render tc7-7 --format pdf --fps 0 --out " + out.string()));  // refused
    CHECK_FALSE(opens_cairo("render tc7-7 --scale 0.3 --out " + out.string()));
    CHECK(opens_cairo("render tc7-7 --scale 0.3 --format pdf --out " + out.string()));
    CHECK(fs::file_size(out / "tc7-7.pdf") > 1000);
}

TEST_CASE("only a command that encodes or decodes a film opens FFmpeg's codec libraries", "[cli][media]") {
    auto opens_ffmpeg = [](const std::string& args) {
        const Run run = testkit::figgen_env("LD_DEBUG=files", args);
        const bool module = run.output.find("file=" FIGGEN_BUILD_DIR "/lib/libfiggen_media.so") != std::string::npos;
        const bool codecs = run.output.find("file=libavcodec.so") != std::string::npos;
        CHECK(module == codecs);  // the codecs come only with the module
        return codecs;
    };
    const fs::path out = fresh_dir("media-loading");
    CHECK_FALSE(opens_ffmpeg("--version"));
    CHECK_FALSE(opens_ffmpeg("list"));
    CHECK_FALSE(opens_ffmpeg("render tc7-1 --fps 0 --out " + out.string()));  // refused
    CHECK_FALSE(opens_ffmpeg("render tc7-1 --format png --out " + out.string()));
    CHECK_FALSE(opens_ffmpeg("render tc7-1 --format frames --scale 0.3 --out " + out.string()));
    CHECK(opens_ffmpeg("render tc7-1 --scale 0.3 --out " + out.string()));  // the MP4
    CHECK(media::probe_video(out / "tc7-1.mp4").frames > 1);
}

TEST_CASE("cmake --install puts figgen and the descriptions in a prefix, and the installed figgen reads them", "[cli][install]") {
    const fs::path prefix = fresh_dir("install");
    const Run install = testkit::run_command(std::string(FIGGEN_CMAKE) + " --install " + FIGGEN_BUILD_DIR +
                                             " --prefix " + prefix.string());
    INFO(install.output);
    REQUIRE(install.status == 0);
    const fs::path installed = prefix / "bin" / "figgen";
    REQUIRE(fs::exists(installed));
    std::size_t descriptions = 0;
    for (const auto& entry : fs::directory_iterator(prefix / "share" / "figgen" / "figures"))
        descriptions += entry.path().extension() == ".toml";
    std::size_t sources = 0;  // what the source tree holds
    for (const auto& entry : fs::directory_iterator(fs::path(FIGGEN_SOURCE_DIR) / "figures"))
        sources += entry.path().extension() == ".toml";
    CHECK(sources > 30);
    CHECK(descriptions == sources);
    // It reads the installed folder, not the source tree: take one away.
    fs::remove(prefix / "share" / "figgen" / "figures" / "tc7-9.toml");
    const Run list = testkit::run_command("env -u FIGGEN_FIGURES_DIR " + installed.string() + " list");
    CHECK(list.status == 0);
    CHECK(list.lines() == static_cast<int>(sources) - 1);
    CHECK_THAT(list.output, !Catch::Contains("tc7-9 "));
    // With its film: the installed figgen opens the installed video module, not the build tree's.
    const Run render = testkit::run_command("env -u FIGGEN_FIGURES_DIR LD_DEBUG=files " + installed.string() +
                                            " render tc7-1 --scale 0.3 --out " + (prefix / "out").string());
    CHECK(render.status == 0);
    CHECK(fs::exists(prefix / "out" / "tc7-1.png"));
    CHECK(fs::exists(prefix / "out" / "tc7-1.mp4"));
    CHECK_THAT(render.output, Catch::Contains("file=" + installed.parent_path().string() + "/../lib") &&
                                  Catch::Contains("/figgen/libfiggen_media.so") &&
                                  !Catch::Contains(FIGGEN_BUILD_DIR "/lib/libfiggen_media.so"));
#ifdef FIGGEN_TEST_MPI
    // And under mpirun the installed MPI module, likewise.
    const Run ranks = testkit::run_command(
#if defined(__SANITIZE_ADDRESS__)
        "ASAN_OPTIONS=detect_leaks=0:intercept_tls_get_addr=0 "  // Open MPI's kept allocations: see test_cluster.cpp
#endif
        "env -u FIGGEN_FIGURES_DIR LD_DEBUG=files OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
        "OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_btl=self,vader mpirun --oversubscribe -n 2 " +
        installed.string() + " render tc7-phase --set trials=2 --out " + (prefix / "out").string());
    CHECK(ranks.status == 0);
    CHECK_THAT(ranks.output, Catch::Contains("/figgen/libfiggen_mpi.so") &&
                                 !Catch::Contains(FIGGEN_BUILD_DIR "/lib/libfiggen_mpi.so"));
#endif
}
