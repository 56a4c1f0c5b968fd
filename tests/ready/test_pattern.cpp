// Ready's pattern files (ready/pattern.cpp): each encoding VTK writes is
// read to the same arrays; a pattern becomes a description that runs;
// what figgen cannot run is refused in one line; and the VTI files figgen
// writes (ready/vti_file.cpp) are read back by VTK itself and continue a
// run exactly.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "description/description.hpp"
#include "ready/pattern.hpp"
#include "figgen_run.hpp"

namespace fs = std::filesystem;
using description::UsageError;

namespace {

const fs::path fixtures = fs::path(FIGGEN_SOURCE_DIR) / "tests/ready/vti";

// tests/ready/vti/make_files.py's values: a[i] = 0.25 i - 3, b[i] = 1 / (i + 1).
double expected(int chemical, int i, bool float64) {
    const double v = chemical == 0 ? 0.25 * i - 3 : 1.0 / (i + 1);
    return float64 ? v : static_cast<double>(static_cast<float>(v));
}

// A fixture's text with every `from` replaced by `to`, as a file of its own.
fs::path edited(const std::string& fixture, const std::string& from, const std::string& to, const std::string& name) {
    std::string text = testkit::slurp(fixtures / fixture);
    REQUIRE(text.find(from) != std::string::npos);
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    const fs::path dir = testkit::fresh_dir("vti-edited");
    testkit::spill(dir / name, text);
    return dir / name;
}

std::string refusal(const fs::path& file) {
    try {
        ready::read_pattern(file, {std::nullopt, true});
    } catch (const UsageError& e) {
        return e.what();
    }
    return "(read)";
}

}  // namespace

TEST_CASE("every encoding VTK writes is read to the same arrays", "[ready]") {
    for (const char* name : {"ascii-f32.vti", "binary-f32.vti", "binary-zlib-f64.vti", "binary-zlib-f32-uint32.vti",
                             "appended-base64-f32.vti", "appended-base64-zlib-f64.vti", "appended-raw-f64.vti",
                             "appended-raw-zlib-f32.vti"}) {
        INFO(name);
        const auto pattern = ready::read_pattern(fixtures / name, {std::nullopt, true});
        REQUIRE(pattern.start);  // apply_when_loading="false": the stored arrays are the start
        const bool float64 = std::string(name).find("f64") != std::string::npos;
        CHECK(pattern.start->float64 == float64);
        CHECK(pattern.start->width == 8);
        CHECK(pattern.start->height == 6);
        REQUIRE(pattern.start->chemicals.size() == 2);
        for (int c = 0; c < 2; ++c)
            for (int i = 0; i < 48; ++i) CHECK(pattern.start->chemicals[c][i] == expected(c, i, float64));
    }
}

TEST_CASE("a Ready pattern becomes the formula description that runs it", "[ready]") {
    const description::Description d = ready::load_pattern(fixtures / "binary-zlib-f64.vti", {"steps=10"});
    CHECK(d.id == "binary-zlib-f64");
    CHECK(d.title == "Test rule");
    CHECK(d.scene == "formula");
    CHECK(d.params["data_type"].value_or(std::string()) == "double");
    CHECK(d.params["D"].value_or(0.0) == 0.5);
    CHECK(d.params["timestep"].value_or(0.0) == Approx(0.1));
    CHECK(d.params["steps"].value_or(0) == 10);
    CHECK(d.params["formula"].value_or(std::string()) == "delta_a = D * laplacian_a;\ndelta_b = D * laplacian_b;\n");
    CHECK(d.panels == std::vector<int>{0, 5, 10});  // 0, N/2 and N
    CHECK(d.style["show"][0].value_or(std::string()) == "b");  // Ready's active chemical
    CHECK(d.style["b_vmax"].value_or(0.0) == 1.0);
    REQUIRE(d.stored_start);
    // A key's origin is the file's element that gave it, or the --set.
    CHECK(d.where("params.D") == "binary-zlib-f64.vti <param name=\"D\">");
    CHECK(d.where("params.formula") == "binary-zlib-f64.vti <formula>");
    CHECK(d.where("style.b_vmax") == "binary-zlib-f64.vti <render_settings>");
    CHECK(d.where("params.steps") == "--set steps=10");
}

TEST_CASE("a pattern's overlays become the description's initial, in Ready's order", "[ready]") {
    const std::string generator = R"(<initial_pattern_generator apply_when_loading="true">
      <overlay chemical="a"><overwrite /><constant value="0.5" /><everywhere /></overlay>
      <overlay chemical="b"><add /><white_noise low="0" high="0.25" /><rectangle><point3D x="0.1" y="0.2" z="0" /><point3D x="0.5" y="0.6" z="1" /></rectangle></overlay>
      <overlay chemical="b"><multiply /><gaussian height="2" sigma="0.1"><point3D x="0.5" y="0.5" z="0.5" /></gaussian><circle radius="0.25"><point3d x="0.5" y="0.5" z="0" /></circle></overlay>
      <overlay chemical="a"><subtract /><parameter name="D" /><pixel x="3" y="2" z="0" /></overlay>
      <overlay chemical="a"><divide /><other_chemical chemical="b" /><pixel x="3" y="-1" z="1" /></overlay>
    </initial_pattern_generator>)";
    const fs::path file = edited("ascii-f32.vti", R"(<initial_pattern_generator apply_when_loading="false" />)",
                                 generator, "overlays.vti");
    const auto pattern = ready::read_pattern(file, {std::nullopt, true});
    CHECK_FALSE(pattern.start);  // zero first, then the overlays
    CHECK_FALSE(pattern.starts_from_arrays);
    const description::Description d = ready::load_pattern(file);
    CHECK(d.where("params.initial[2].shapes") == "overlays.vti <overlay> 3 of <initial_pattern_generator>");
    const toml::array& initial = *d.params["initial"].as_array();
    REQUIRE(initial.size() == 4);  // the last one's pixel lies off the grid (y = -1): it never applies
    CHECK(initial[0].as_table()->at("fill").value_or(std::string()) == "constant");
    CHECK(initial[1].as_table()->at("operation").value_or(std::string()) == "add");
    const toml::table& rect = *initial[1].as_table()->at("shapes").as_array()->get(0)->as_table();
    CHECK(rect.at("from").as_array()->get(1)->value_or(0.0) == Approx(0.2));
    CHECK(initial[2].as_table()->at("centre").as_array()->get(0)->value_or(0.0) == 0.5);
    CHECK(initial[3].as_table()->at("parameter").value_or(std::string()) == "D");
    // And it runs: every overlay is one the scene accepts.
    const fs::path out = testkit::fresh_dir("vti-overlays");
    const auto run = testkit::figgen("render " + file.string() + " --set steps=2 --format png --scale 0.3 --out " + out.string());
    INFO(run.output);
    CHECK(run.status == 0);
}

TEST_CASE("what figgen cannot run is refused in one line that says what", "[ready]") {
    using Catch::Contains;
    CHECK_THAT(refusal(edited("ascii-f32.vti", R"(type="formula")", R"(type="kernel")", "kernel.vti")),
               Contains("no <kernel> in <rule>"));
    CHECK_THAT(refusal(edited("ascii-f32.vti", R"(type="formula")", R"(type="neural")", "neural.vti")),
               Contains("its rule is type \"neural\": figgen runs formula, kernel and Ready's inbuilt Gray-Scott rules"));
    CHECK_THAT(refusal(edited("ascii-f32.vti", R"(WholeExtent="0 7 0 5 0 0")", R"(WholeExtent="0 4095 0 4095 0 1")",
                              "big3d.vti")),
               Contains("its extent is 4096 x 4096 x 2: figgen runs grids of up to 4096 cells a side and 4096 x 4096 "
                        "cells in all"));
    CHECK_THAT(refusal(edited("ascii-f32.vti", R"(type="ImageData")", R"(type="UnstructuredGrid")", "mesh.vti")),
               Contains("no <UnstructuredGrid> in <VTKFile>"));
    CHECK_THAT(refusal(edited("binary-f32.vti", R"(byte_order="LittleEndian")", R"(byte_order="BigEndian")", "big.vti")),
               Contains("figgen reads LittleEndian"));
    CHECK_THAT(refusal(edited("ascii-f32.vti", R"(Name="b")", R"(Name="q")", "missing.vti")),
               Contains("holds neither arrays a, b, ... nor one of 2 components"));
    CHECK_THAT(refusal(edited("ascii-f32.vti", R"(type="Float32" Name="a")", R"(type="Int32" Name="a")", "int.vti")),
               Contains("<DataArray Name=\"a\"> is type \"Int32\": figgen reads Float32 and Float64"));
    CHECK_THAT(refusal(edited("ascii-f32.vti", "RD", "XX", "nord.vti")),
               Contains("no <RD> in <VTKFile>"));
    CHECK_THAT(refusal(edited("ascii-f32.vti", "<VTKFile", "<VTKFile <", "notxml.vti")),
               Contains("not well-formed XML (line 2: XML_ERROR_"));
    CHECK_THAT(refusal(edited("ascii-f32.vti", R"(<param name="D">0.5</param>)", R"(<param name="D">nan</param>)", "nan.vti")),
               Contains("<param name=\"D\"> is \"nan\", not a finite number"));
    CHECK_THAT(refusal(edited("ascii-f32.vti", R"(<param name="D">)", R"(<param name="width">)", "clash.vti")),
               Contains("<param name=\"width\"> is a key of figgen's formula scene"));
    CHECK_THAT(refusal(fixtures / "no-such-file.vti"), Contains("not a regular file"));
    // A small file may claim arrays far larger than itself (zlib): refused
    // before any is decoded. 9 chemicals of 4096 x 4096 as doubles: 1152 MiB.
    const fs::path huge = edited("ascii-f32.vti", R"(WholeExtent="0 7 0 5 0 0")", R"(WholeExtent="0 4095 0 4095 0 0")", "huge.vti");
    std::string text = testkit::slurp(huge);
    text.replace(text.find(R"(number_of_chemicals="2")"), 23, R"(number_of_chemicals="9")");
    testkit::spill(huge, text);
    CHECK_THAT(refusal(huge), Contains("its stored arrays would take 1152 MiB as doubles: figgen reads at most 1024 MiB"));
    // Cut, corrupt or lying data: a header that claims more than the extent,
    // zlib blocks that do not inflate, base64 cut short.
    const std::string zlib = testkit::slurp(fixtures / "binary-zlib-f32-uint32.vti");
    const std::size_t data = zlib.find(">", zlib.find("Name=\"a\"")) + 1;
    std::string cut = zlib;
    cut.replace(data, 30, std::string(30, 'A'));
    const fs::path dir = testkit::fresh_dir("vti-broken");
    testkit::spill(dir / "broken.vti", cut);
    CHECK_THAT(refusal(dir / "broken.vti"), Contains("broken.vti: "));
    std::string shorter = zlib;
    shorter.erase(data + 20, 24);
    testkit::spill(dir / "short.vti", shorter);
    CHECK_THAT(refusal(dir / "short.vti"), Contains("short.vti: "));
    // On the command line: exit status 2, one line, nothing written.
    const fs::path out = testkit::fresh_dir("vti-refused");
    const auto run = testkit::figgen("render " + (dir / "short.vti").string() + " --out " + out.string());
    CHECK(run.status == 2);
    CHECK(run.lines() == 1);
    CHECK(fs::is_empty(out));
}

TEST_CASE("figgen's VTI file is read back by VTK with the same arrays, and continues the run", "[ready]") {
    const fs::path out = testkit::fresh_dir("vti-out");
    const fs::path pattern = fixtures / "binary-zlib-f32-uint32.vti";
    const auto run = testkit::figgen("render " + pattern.string() + " --set steps=6 --format png,vti --scale 0.3 --out " +
                                     out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    const auto meta = nlohmann::json::parse(testkit::slurp(out / "binary-zlib-f32-uint32.json"));
    const std::string last_hash = meta["panels"].back()["state_sha256"];
    CHECK(meta["vti"]["file"] == "binary-zlib-f32-uint32.vti");
    // VTK's own reader (Debian's python3-vtk9): the arrays, as doubles in
    // figgen's order (a then b), hash as the figure's last panel's state.
    const std::string script =
        "import hashlib, vtkmodules.all as v\n"
        "from vtkmodules.util.numpy_support import vtk_to_numpy\n"
        "r = v.vtkXMLImageDataReader(); r.SetFileName('" + (out / "binary-zlib-f32-uint32.vti").string() + "'); r.Update()\n"
        "im = r.GetOutput(); d = im.GetPointData()\n"
        "print(im.GetDimensions(), d.GetArray('a').GetDataTypeAsString())\n"
        "h = hashlib.sha256()\n"
        "for n in 'ab': h.update(vtk_to_numpy(d.GetArray(n)).astype('<f8').tobytes())\n"
        "print(h.hexdigest())\n";
    testkit::spill(out / "read.py", script);
    const auto vtk = testkit::run_command("/usr/bin/python3 " + (out / "read.py").string());
    INFO(vtk.output);
    REQUIRE(vtk.status == 0);
    CHECK_THAT(vtk.output, Catch::Contains("(8, 6, 1) float"));
    CHECK_THAT(vtk.output, Catch::Contains(last_hash));
    // figgen reads it as Ready would: 6 steps from it are 12 from the start.
    const fs::path again = testkit::fresh_dir("vti-again");
    const auto more = testkit::figgen("render " + (out / "binary-zlib-f32-uint32.vti").string() +
                                      " --set steps=6 --format png --scale 0.3 --out " + again.string());
    INFO(more.output);
    REQUIRE(more.status == 0);
    const auto twelve = testkit::figgen("render " + pattern.string() + " --set steps=12 --format png --scale 0.3 --out " +
                                        again.string() + " --set id=twelve");
    REQUIRE(twelve.status == 0);
    const auto m6 = nlohmann::json::parse(testkit::slurp(again / "binary-zlib-f32-uint32.json"));
    const auto m12 = nlohmann::json::parse(testkit::slurp(again / "twelve.json"));
    CHECK(m6["panels"].back()["step"] == 6);
    CHECK(m12["panels"].back()["step"] == 12);
    CHECK(m6["panels"].back()["state_sha256"] == m12["panels"].back()["state_sha256"]);
}

TEST_CASE("figgen convert prints the description, or writes OUT/ID.toml", "[ready]") {
    const auto printed = testkit::figgen("convert " + (fixtures / "ascii-f32.vti").string());
    REQUIRE(printed.status == 0);
    CHECK_THAT(printed.output, Catch::Contains("scene = \"formula\""));
    CHECK_THAT(printed.output, Catch::Contains("starts from them"));  // the stored arrays: said in a comment
    const fs::path out = testkit::fresh_dir("vti-convert");
    const auto written = testkit::figgen("convert " + (fixtures / "ascii-f32.vti").string() + " --out " + out.string());
    REQUIRE(written.status == 0);
    // What it wrote is a description that loads as the pattern does, less the stored start.
    const description::Description d = description::load_description(out / "ascii-f32.toml");
    const description::Description p = ready::load_pattern(fixtures / "ascii-f32.vti");
    CHECK(d.params == p.params);
    CHECK(d.style == p.style);
    CHECK(d.panels == p.panels);
    const auto refused = testkit::figgen("convert " + (fixtures / "make_files.py").string());
    CHECK(refused.status == 2);
}

// The fixture as a 1-D or 3-D pattern whose start is drawn by its overlays:
// a = 0.5 everywhere, b = 1 in a ball (a segment in 1-D) at the centre.
fs::path grid_pattern(const std::string& extent, const std::string& name) {
    std::string text = testkit::slurp(fixtures / "ascii-f32.vti");
    for (const std::string from : {"WholeExtent=\"0 7 0 5 0 0\"", "Extent=\"0 7 0 5 0 0\""}) {
        const std::size_t at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), from.substr(0, from.find('"') + 1) + extent + "\"");
    }
    const std::string generator = R"(<initial_pattern_generator apply_when_loading="false" />)";
    text.replace(text.find(generator), generator.size(), R"(<initial_pattern_generator apply_when_loading="true">
      <overlay chemical="a"><overwrite /><constant value="0.5" /><everywhere /></overlay>
      <overlay chemical="b"><overwrite /><constant value="1" /><circle radius="0.2"><point3D x="0.5" y="0.5" z="0.5" /></circle></overlay>
    </initial_pattern_generator>)");
    const fs::path dir = testkit::fresh_dir("vti-grids");
    testkit::spill(dir / name, text);
    return dir / name;
}

TEST_CASE("1-D and 3-D patterns run, write VTI files VTK reads, and continue from them", "[ready]") {
    struct Case {
        std::string extent, name, dimensions;
    };
    for (const Case& c : {Case{"0 15 0 0 0 0", "line.vti", "(16, 1, 1)"}, Case{"0 7 0 5 0 3", "solid.vti", "(8, 6, 4)"}}) {
        const fs::path pattern = grid_pattern(c.extent, c.name);
        const std::string id = fs::path(c.name).stem().string();
        const fs::path out = testkit::fresh_dir("vti-grids-out");
        const auto run = testkit::figgen("render " + pattern.string() + " --set steps=6 --format png,pdf,vti --scale 0.5 --out " +
                                         out.string());
        INFO(run.output);
        REQUIRE(run.status == 0);
        CHECK(fs::file_size(out / (id + ".pdf")) > 1000);
        const auto meta = nlohmann::json::parse(testkit::slurp(out / (id + ".json")));
        const std::string last_hash = meta["panels"].back()["state_sha256"];
        const std::string script =
            "import hashlib, vtkmodules.all as v\n"
            "from vtkmodules.util.numpy_support import vtk_to_numpy\n"
            "r = v.vtkXMLImageDataReader(); r.SetFileName('" + (out / (id + ".vti")).string() + "'); r.Update()\n"
            "im = r.GetOutput(); d = im.GetPointData()\n"
            "print(im.GetDimensions())\n"
            "h = hashlib.sha256()\n"
            "for n in 'ab': h.update(vtk_to_numpy(d.GetArray(n)).astype('<f8').tobytes())\n"
            "print(h.hexdigest())\n";
        testkit::spill(out / "read.py", script);
        const auto vtk = testkit::run_command("/usr/bin/python3 " + (out / "read.py").string());
        INFO(vtk.output);
        REQUIRE(vtk.status == 0);
        CHECK_THAT(vtk.output, Catch::Contains(c.dimensions));
        CHECK_THAT(vtk.output, Catch::Contains(last_hash));
        // 6 steps from figgen's file are 12 from the pattern's start.
        const fs::path again = testkit::fresh_dir("vti-grids-again");
        REQUIRE(testkit::figgen("render " + (out / (id + ".vti")).string() + " --set steps=6 --format png --scale 0.5 --set id=six --out " +
                                again.string()).status == 0);
        REQUIRE(testkit::figgen("render " + pattern.string() + " --set steps=12 --format png --scale 0.5 --set id=twelve --out " +
                                again.string()).status == 0);
        const auto m6 = nlohmann::json::parse(testkit::slurp(again / "six.json"));
        const auto m12 = nlohmann::json::parse(testkit::slurp(again / "twelve.json"));
        CHECK(m6["panels"].back()["state_sha256"] == m12["panels"].back()["state_sha256"]);
    }
}

TEST_CASE("Ready's inbuilt Gray-Scott reads as the formula it computes", "[ready]") {
    std::string text = testkit::slurp(fixtures / "ascii-f32.vti");
    const std::size_t from = text.find("<rule"), to = text.find("</rule>") + 7;
    text.replace(from, to - from, R"(<rule type="inbuilt" name="Gray-Scott" wrap="0">
      <param name="timestep">1</param><param name="D_a">0.2</param><param name="D_b">0.1</param>
      <param name="k">0.064</param><param name="F">0.035</param></rule>)");
    const fs::path dir = testkit::fresh_dir("vti-inbuilt");
    testkit::spill(dir / "inbuilt.vti", text);
    const description::Description d = ready::load_pattern(dir / "inbuilt.vti");
    CHECK(d.params["block_x"].value_or(0) == 1);
    CHECK(d.params["ready_edges"].value_or(true) == false);
    CHECK(d.params["wrap"].value_or(true) == false);
    CHECK_THAT(d.params["formula"].value_or(std::string()), Catch::Contains("float dda = a_s + a_n + a_w + a_e + a_d + a_u - 6*a;"));
    CHECK(d.where("params.formula") == "inbuilt.vti <rule type=\"inbuilt\" name=\"Gray-Scott\">");
    const auto run = testkit::figgen("render " + (dir / "inbuilt.vti").string() + " --set steps=3 --format png --scale 0.3 --out " +
                                     (dir / "out").string());
    INFO(run.output);
    CHECK(run.status == 0);
}
