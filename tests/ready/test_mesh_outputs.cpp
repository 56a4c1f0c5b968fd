// A mesh run on the command line: its last step as Ready's own file
// (--format vtu), read back by VTK (Debian's python3-vtk9) and continued by
// figgen; and damaged mesh pattern files refused in one line, exit 2,
// before anything is written.

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"
#include "media/png_io.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path fixtures = fs::path(FIGGEN_SOURCE_DIR) / "tests/ready/vtu";

// The fixture's text with `from` replaced by `to` (present once).
std::string edited(const std::string& name, const std::string& from, const std::string& to) {
    std::string text = testkit::slurp(fixtures / name);
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
}

// VTK's reading of a .vtu: its cell count, array a's type, the SHA-256 of
// every chemical (a, b, ... as `chemicals` says) as doubles one after
// another, and the <RD> element's rule line.
std::string vtk_reading(const fs::path& file, const fs::path& script, int chemicals) {
    testkit::spill(script,
                   "import hashlib, vtkmodules.all as v\n"
                   "from vtkmodules.util.numpy_support import vtk_to_numpy\n"
                   "r = v.vtkXMLUnstructuredGridReader(); r.SetFileName('" + file.string() + "'); r.Update()\n"
                   "g = r.GetOutput(); d = g.GetCellData()\n"
                   "print('cells', g.GetNumberOfCells(), d.GetArray('a').GetDataTypeAsString())\n"
                   "h = hashlib.sha256()\n"
                   "for n in 'abcdefgh'[:" + std::to_string(chemicals) + "]:\n"
                   "    h.update(vtk_to_numpy(d.GetArray(n)).astype('<f8').tobytes())\n"
                   "print(h.hexdigest())\n"
                   "import re\n"
                   "print(re.search(r'<rule [^>]*>', open('" + file.string() + "').read()).group(0))\n");
    const auto run = testkit::run_command("/usr/bin/python3 " + script.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    return run.output;
}

}  // namespace

TEST_CASE("a mesh run's VTU file is read by VTK with the same cells, and continues the run", "[ready][vtu]") {
    SECTION("a formula on a mesh (Ready's formula, edge neighbours)") {
        const fs::path out = testkit::fresh_dir("vtu-out");
        const fs::path pattern = fixtures / "ascii-f32.vtu";
        const auto run = testkit::figgen("render " + pattern.string() + " --set steps=6 --format png,vtu --scale 0.3 --out " +
                                         out.string());
        INFO(run.output);
        REQUIRE(run.status == 0);
        const auto meta = nlohmann::json::parse(testkit::slurp(out / "ascii-f32.json"));
        CHECK(meta["vtu"]["file"] == "ascii-f32.vtu");
        const std::string read = vtk_reading(out / "ascii-f32.vtu", out / "read.py", 2);
        CHECK_THAT(read, Catch::Contains("cells 4 float"));
        CHECK_THAT(read, Catch::Contains(meta["panels"].back()["state_sha256"].get<std::string>()));
        CHECK_THAT(read, Catch::Contains("type=\"formula\" neighborhood_type=\"edge\""));
        // figgen reads it as Ready would: 6 steps from it are 12 from the start.
        const fs::path again = testkit::fresh_dir("vtu-again");
        const auto more = testkit::figgen("render " + (out / "ascii-f32.vtu").string() +
                                          " --set steps=6 --format png --scale 0.3 --out " + again.string());
        INFO(more.output);
        REQUIRE(more.status == 0);
        const auto twelve = testkit::figgen("render " + pattern.string() + " --set steps=12 --format png --scale 0.3 --out " +
                                            again.string() + " --set id=twelve");
        REQUIRE(twelve.status == 0);
        const auto m6 = nlohmann::json::parse(testkit::slurp(again / "ascii-f32.json"));
        const auto m12 = nlohmann::json::parse(testkit::slurp(again / "twelve.json"));
        CHECK(m12["panels"].back()["step"] == 12);
        CHECK(m6["panels"].back()["state_sha256"] == m12["panels"].back()["state_sha256"]);
    }
    SECTION("a kernel on a Penrose tiling (the catalog's glider)") {
        const fs::path out = testkit::fresh_dir("vtu-kernel");
        const std::string small = " --set steps=4 --set 'figure.panels=[0, 4]' --set 'animation.steps=[0, 4]' --scale 0.3 --out ";
        const auto run = testkit::figgen("render life-penrose-glider --format png,vtu" + small + out.string());
        INFO(run.output);
        REQUIRE(run.status == 0);
        const auto meta = nlohmann::json::parse(testkit::slurp(out / "life-penrose-glider.json"));
        const std::string read = vtk_reading(out / "life-penrose-glider.vtu", out / "read.py", 1);
        CHECK_THAT(read, Catch::Contains("cells 3010 float"));
        CHECK_THAT(read, Catch::Contains(meta["panels"].back()["state_sha256"].get<std::string>()));
        CHECK_THAT(read, Catch::Contains("type=\"kernel\" neighborhood_type=\"vertex\""));
        const auto more = testkit::figgen("render " + (out / "life-penrose-glider.vtu").string() +
                                          " --set steps=4 --format png --scale 0.3 --set id=more --out " + out.string());
        INFO(more.output);
        REQUIRE(more.status == 0);
        const auto eight = testkit::figgen("render life-penrose-glider --format png --set steps=8 --set "
                                           "'figure.panels=[0, 8]' --set 'animation.steps=[0, 8]' --scale 0.3 --set id=eight --out " +
                                           out.string());
        REQUIRE(eight.status == 0);
        const auto m4 = nlohmann::json::parse(testkit::slurp(out / "more.json"));
        const auto m8 = nlohmann::json::parse(testkit::slurp(out / "eight.json"));
        CHECK(m4["panels"].back()["state_sha256"] == m8["panels"].back()["state_sha256"]);
        CHECK(m4["panels"].back()["state_sha256"] != meta["panels"].back()["state_sha256"]);  // the glider moved
    }
    SECTION("an image's figure has no VTU file, nor a mesh's a VTI file") {
        const auto image = testkit::figgen("render fx-brusselator --format vtu --out " +
                                           testkit::fresh_dir("vtu-image").string());
        CHECK(image.status == 2);
        CHECK(image.lines() == 1);
        CHECK_THAT(image.output, Catch::Contains("--format vtu: fx-brusselator is a formula figure; the scenes that "
                                                 "write a VTU file are mesh"));
        const auto mesh = testkit::figgen("render life-penrose-glider --format vti --out " +
                                          testkit::fresh_dir("vti-mesh").string());
        CHECK(mesh.status == 2);
        CHECK_THAT(mesh.output, Catch::Contains("--format vti: life-penrose-glider is a mesh figure"));
    }
}

TEST_CASE("a damaged mesh pattern is refused in one line, exit 2, before anything is written", "[ready][vtu][cli]") {
    const fs::path dir = testkit::fresh_dir("vtu-damaged");
    struct Damage {
        const char* name;
        std::string text;
        const char* said;
    };
    const Damage damages[] = {
        {"lying-header.vtu", edited("ascii-f32.vtu", "NumberOfCells=\"4\"", "NumberOfCells=\"4000\""),
         "holds 4 numbers, not 4000"},
        {"missing-point.vtu", edited("ascii-f32.vtu", "0 1 5 4 1 2", "0 1 5 4 1 8"),
         "cell 1 the point 8: <Piece NumberOfPoints> is 8, so indices run from 0 to 7"},
        {"no-chemical-b.vtu", edited("ascii-f32.vtu", "Name=\"b\"", "Name=\"q\""), "no array \"b\""},
        {"bad-formula.vtu", edited("ascii-f32.vtu", "delta_a = D * laplacian_a;", "delta_a = D * laplacian_a +;"),
         "formula"},
    };
    for (const Damage& d : damages) {
        INFO(d.name);
        testkit::spill(dir / d.name, d.text);
        const fs::path out = dir / (std::string(d.name) + "-out");
        const auto run = testkit::figgen("render " + (dir / d.name).string() + " --set steps=2 --out " + out.string());
        INFO(run.output);
        CHECK(run.status == 2);
        CHECK(run.lines() == 1);
        CHECK_THAT(run.output, Catch::Contains(d.name));
        CHECK_THAT(run.output, Catch::Contains(d.said));
        CHECK_FALSE(fs::exists(out));
    }
}

TEST_CASE("a mesh kernel that reads outside its buffers stops with its line, step and cell, and writes nothing",
          "[ready][vtu][cli]") {
    const fs::path dir = testkit::fresh_dir("mesh-hostile");
    const std::string kernel = R"(__kernel void rd_compute(__global float* a_in, __global float* a_out,
        __global int* neighbor_indices, __global float* neighbor_weights, const int max_neighbors)
{
    const int x = get_global_id(0);
    int k = x < 3000 ? x : x + 100000;
    a_out[x] = a_in[k];
})";
    testkit::spill(dir / "hostile.toml", "id = \"hostile\"\ntitle = \"t\"\nscene = \"mesh\"\n[params]\nchemicals = 1\n"
                                         "kernel = \"\"\"" + kernel + "\"\"\"\nmesh = \"penrose-goucher-glider\"\n"
                                         "steps = 3\n[figure]\npanels = [0, 3]\nsize = [300, 200]\n");
    const fs::path out = dir / "out";
    const auto run = testkit::figgen("render " + (dir / "hostile.toml").string() + " --out " + out.string());
    INFO(run.output);
    CHECK(run.status == 1);
    CHECK(run.lines() == 1);
    CHECK_THAT(run.output, Catch::Contains("kernel line 6, step 1, work item (3000, 0, 0): index 103000 of a_in is "
                                           "outside 0 to 3009"));
    CHECK((!fs::exists(out) || fs::is_empty(out)));
}

TEST_CASE("a solid lattice is drawn as its occupied cells inside its box, from above three-quarters", "[ready][vtu]") {
    // Two polyhedra side by side (x 0..1 and 1..2), a = 0.2 and 0.9, still (D = 0): of the colour
    // range 0..1, only the second cell is at or above the middle, and drawn.
    const fs::path out = testkit::fresh_dir("mesh-lattice");
    std::string text = edited("polyhedra-ascii.vtu", "number_of_chemicals=\"2\"", "number_of_chemicals=\"1\"");
    text.erase(text.find("delta_b = D * laplacian_b;"), 26);
    text.replace(text.find("0.5 1.5"), 7, "0.2 0.9");
    text.replace(text.find("name=\"D\">0.5<"), 13, "name=\"D\">0.0<");
    fs::create_directories(out / "in");
    testkit::spill(out / "in" / "polyhedra-ascii.vtu", text);
    const auto run = testkit::figgen("render " + (out / "in" / "polyhedra-ascii.vtu").string() +
                                     " --set steps=2 --set figure.panels=[2] --no-video --set figure.size=[500,300] --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    const nlohmann::json meta = nlohmann::json::parse(testkit::slurp(out / "polyhedra-ascii.json"));
    CHECK(meta["mesh"]["drawn_as"] == "solid");
    CHECK(meta["mesh"]["view"] == nlohmann::json({{"azimuth", 35.0}, {"elevation", 25.0}}));
    const render::Image png = media::read_png(out / "polyhedra-ascii.png").image;
    // The box's edges are grey (0.55); the drawn cell is coloured. Their extents in x, across the page.
    int grey = 0, coloured = 0, grey_lo = png.width, grey_hi = -1, cell_lo = png.width, cell_hi = -1;
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width * 7 / 10; ++x) {  // the colour bar is at the right
            const std::uint8_t* p = png.pixel(x, y);
            const int spread = std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]});
            if (spread < 8 && p[0] > 110 && p[0] < 170) {
                ++grey;
                grey_lo = std::min(grey_lo, x), grey_hi = std::max(grey_hi, x);
            } else if (spread > 80) {
                ++coloured;
                cell_lo = std::min(cell_lo, x), cell_hi = std::max(cell_hi, x);
            }
        }
    CHECK(grey > 200);
    CHECK(coloured > 2000);
    // The cell is at x 1..2 of a box 0..2: the box's empty half shows left of it.
    const int left = std::min(grey_lo, cell_lo), right = std::max(grey_hi, cell_hi);
    CHECK(grey_lo < cell_lo - 20);
    CHECK(cell_lo > left + (right - left) / 4);
}
