// Ready's mesh files (ready/vtu.cpp): each encoding VTK writes reads to the
// same mesh and arrays; a damaged file is refused in one line naming what
// is wrong; what figgen writes reads back to the same bits, and VTK itself
// (Debian's python3-vtk9) reads it as Ready does, <RD> and all.
#include <catch2/catch.hpp>

#include <glib.h>
#include <tinyxml2.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"
#include "ready/vtu.hpp"
#include "sim/mesh/mesh.hpp"

namespace fs = std::filesystem;
using ready::vtu::DataError;
using ready::vtu::UnstructuredGrid;

namespace {

const fs::path fixtures = fs::path(FIGGEN_SOURCE_DIR) / "tests/ready/vtu";

// tests/ready/vtu/make_files.py's mesh and values.
const std::vector<std::vector<std::int64_t>> polygons = {{0, 1, 5, 4}, {1, 2, 6}, {1, 6, 5}, {2, 3, 7, 6}};

double rounded(double v, bool float64) { return float64 ? v : static_cast<double>(static_cast<float>(v)); }

void check_fixture_mesh(const UnstructuredGrid& g, bool float64) {
    const sim::mesh::Mesh& m = g.mesh;
    REQUIRE(m.point_count() == 8);
    REQUIRE(m.cell_count() == 4);
    CHECK(g.points_float64 == float64);
    for (std::size_t i = 0; i < 8; ++i) {
        CHECK(m.points[3 * i] == static_cast<double>(i % 4));
        CHECK(m.points[3 * i + 1] == static_cast<double>(i / 4));
        CHECK(m.points[3 * i + 2] == rounded(0.125 * static_cast<double>(i), float64));
    }
    std::vector<std::int64_t> ids, offsets = {0};
    for (const auto& p : polygons) {
        ids.insert(ids.end(), p.begin(), p.end());
        offsets.push_back(static_cast<std::int64_t>(ids.size()));
    }
    CHECK(m.point_ids == ids);
    CHECK(m.offsets == offsets);
    CHECK(m.types == std::vector<std::uint8_t>(4, sim::mesh::cell_type::polygon));
    CHECK(m.faces.empty());
    REQUIRE(g.cell_data.size() == 3);
    CHECK(g.cell_data[0].name == "a");
    CHECK(g.cell_data[1].name == "b");
    CHECK(g.cell_data[2].name == "v");
    CHECK(g.cell_data[2].components == 3);
    for (int c = 0; c < 4; ++c) {
        CHECK(g.cell_data[0].values[c] == rounded(0.25 * c - 3, float64));
        CHECK(g.cell_data[1].values[c] == rounded(1.0 / (c + 1), float64));
        CHECK(g.cell_data[2].values[3 * c] == c);
        CHECK(g.cell_data[2].values[3 * c + 1] == -c);
        CHECK(g.cell_data[2].values[3 * c + 2] == 0.5 * c);
    }
    for (const auto& a : g.cell_data) CHECK(a.float64 == float64);
    // The <RD> element, for the caller to read the rule from.
    tinyxml2::XMLDocument rd;
    REQUIRE(rd.Parse(g.rd.c_str()) == tinyxml2::XML_SUCCESS);
    REQUIRE(rd.RootElement());
    CHECK(std::string(rd.RootElement()->Name()) == "RD");
    REQUIRE(rd.RootElement()->FirstChildElement("rule"));
    CHECK(std::string(rd.RootElement()->FirstChildElement("rule")->Attribute("name")) == "Test rule");
}

// The one-line message `text` is refused with.
std::string refusal(const std::string& text) {
    try {
        ready::vtu::read_vtu(text);
    } catch (const DataError& e) {
        return e.what();
    }
    return "(read)";
}

// A fixture's text with `from` (which it must hold) replaced by `to`.
std::string edited(const std::string& fixture, const std::string& from, const std::string& to) {
    std::string text = testkit::slurp(fixtures / fixture);
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
}

void check_one_line(const std::string& message, const std::string& names) {
    INFO(message);
    CHECK(message != "(read)");
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.size() < 400);
    CHECK_THAT(message, Catch::Contains(names));
}

std::string base64(const std::string& bytes) {
    gchar* text = g_base64_encode(reinterpret_cast<const guchar*>(bytes.data()), bytes.size());
    std::string s(text);
    g_free(text);
    return s;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void check_same(const UnstructuredGrid& a, const UnstructuredGrid& b) {
    CHECK(same_bits(a.mesh.points, b.mesh.points));
    CHECK(a.mesh.offsets == b.mesh.offsets);
    CHECK(a.mesh.point_ids == b.mesh.point_ids);
    CHECK(a.mesh.types == b.mesh.types);
    CHECK(a.mesh.faces == b.mesh.faces);
    CHECK(a.mesh.face_offsets == b.mesh.face_offsets);
    CHECK(a.points_float64 == b.points_float64);
    REQUIRE(a.cell_data.size() == b.cell_data.size());
    for (std::size_t i = 0; i < a.cell_data.size(); ++i) {
        CHECK(a.cell_data[i].name == b.cell_data[i].name);
        CHECK(a.cell_data[i].components == b.cell_data[i].components);
        CHECK(a.cell_data[i].float64 == b.cell_data[i].float64);
        CHECK(same_bits(a.cell_data[i].values, b.cell_data[i].values));
    }
    CHECK(a.rd == b.rd);
}

}  // namespace

TEST_CASE("every encoding VTK writes reads to the same mesh and arrays", "[vtu]") {
    const std::pair<const char*, bool> files[] = {
        {"ascii-f32.vtu", false},           {"binary-f32-int32.vtu", false},         {"binary-zlib-f64.vtu", true},
        {"binary-zlib-f32-uint32.vtu", false}, {"appended-base64-f32.vtu", false},   {"appended-base64-zlib-f64.vtu", true},
        {"appended-raw-f64-int32.vtu", true},  {"appended-raw-zlib-f32.vtu", false}};
    for (const auto& [file, float64] : files) {
        INFO(file);
        check_fixture_mesh(ready::vtu::read_vtu(testkit::slurp(fixtures / file)), float64);
    }
}

TEST_CASE("polyhedra are read with their faces", "[vtu]") {
    for (const char* file : {"polyhedra-binary-zlib.vtu", "polyhedra-ascii.vtu"}) {
        INFO(file);
        const UnstructuredGrid g = ready::vtu::read_vtu(testkit::slurp(fixtures / file));
        CHECK(g.mesh.cell_count() == 2);
        CHECK(g.mesh.point_count() == 12);
        CHECK(g.mesh.types == std::vector<std::uint8_t>(2, sim::mesh::cell_type::polyhedron));
        CHECK(g.mesh.face_offsets == std::vector<std::int64_t>{31, 62});  // 6 faces of 4 points: 1 + 6 * 5 each
        REQUIRE(g.mesh.faces.size() == 62);
        CHECK(std::vector<std::int64_t>(g.mesh.faces.begin(), g.mesh.faces.begin() + 6) ==
              std::vector<std::int64_t>{6, 4, 0, 3, 2, 1});
        // The face the two share, in each one's list.
        CHECK(sim::mesh::neighbours(g.mesh, sim::mesh::Kind::face).indices == std::vector<int>{1, 0});
    }
}

TEST_CASE("a damaged mesh file is refused in one line naming what is wrong", "[vtu]") {
    SECTION("NumberOfCells that the arrays do not hold") {
        check_one_line(refusal(edited("ascii-f32.vtu", "NumberOfCells=\"4\"", "NumberOfCells=\"5\"")),
                       "holds 4 numbers, not 5");
        check_one_line(refusal(edited("binary-zlib-f64.vtu", "NumberOfCells=\"4\"", "NumberOfCells=\"5\"")),
                       "<DataArray Name=\"types\">: an array's header says it holds 4 bytes");
        check_one_line(refusal(edited("ascii-f32.vtu", "NumberOfCells=\"4\"", "NumberOfCells=\"4000001\"")),
                       "<Piece NumberOfCells> is \"4000001\", not an integer from 0 to 4000000");
        check_one_line(refusal(edited("ascii-f32.vtu", "NumberOfPoints=\"8\"", "NumberOfPoints=\"-8\"")),
                       "<Piece NumberOfPoints> is \"-8\"");
    }
    SECTION("a point index past the points") {
        const std::string m = refusal(edited("ascii-f32.vtu", "0 1 5 4 1 2", "0 1 5 4 1 8"));
        check_one_line(m, "<DataArray Name=\"connectivity\">");
        CHECK_THAT(m, Catch::Contains("cell 1 the point 8: <Piece NumberOfPoints> is 8, so indices run from 0 to 7"));
        check_one_line(refusal(edited("ascii-f32.vtu", "0 1 5 4 1 2", "0 1 5 -4 1 2")), "cell 0 the point -4");
    }
    SECTION("offsets that decrease, or do not end at the connectivity's end") {
        const std::string m = refusal(edited("ascii-f32.vtu", "4 7 10 14", "4 10 7 14"));
        check_one_line(m, "<DataArray Name=\"offsets\"> gives cell 2 the end 7, before the previous cell's 10");
        check_one_line(refusal(edited("ascii-f32.vtu", "4 7 10 14", "4 7 10 13")),
                       "<DataArray Name=\"connectivity\"> (of 13 point indices, as the last offset says): an ascii "
                       "array holds more than 13 numbers");
        check_one_line(refusal(edited("ascii-f32.vtu", "4 7 10 14", "4 7 10 90")), "gives cell 3 (VTK_POLYGON) 80 points");
    }
    SECTION("cell types and their points") {
        check_one_line(refusal(edited("ascii-f32.vtu", "7 7 7 7", "7 7 7 3")),
                       "<DataArray Name=\"types\"> gives cell 3 type 3: figgen reads VTK's types 5 (triangle)");
        check_one_line(refusal(edited("ascii-f32.vtu", "7 7 7 7", "5 7 7 7")),
                       "gives cell 0 (VTK_TRIANGLE) 4 points: it has 3");
    }
    SECTION("points that are not finite, or not three a point") {
        check_one_line(refusal(edited("ascii-f32.vtu", "0 0 0 1 0 0.125", "0 0 0 1 0 nan")),
                       "<Points> <DataArray Name=\"Points\">");
        check_one_line(refusal(edited("ascii-f32.vtu", "0 0 0 1 0 0.125", "0 0 0 1 0 inf")), "not a finite number");
        check_one_line(refusal(edited("ascii-f32.vtu", "Name=\"Points\" NumberOfComponents=\"3\"",
                                      "Name=\"Points\" NumberOfComponents=\"2\"")),
                       "NumberOfComponents is 2, not 3");
    }
    SECTION("a polyhedron's faces that do not match its offsets or points") {
        check_one_line(refusal(edited("polyhedra-ascii.vtu", "31 62", "30 62")), "cell 0's face offset is 30");
        check_one_line(refusal(edited("polyhedra-ascii.vtu", "6 4 0 3 2 1", "6 4 0 3 2 11")),
                       "<Cells>: cell 0's face 0 names a point that is not among the cell's");
        check_one_line(refusal(edited("polyhedra-ascii.vtu", "6 4 0 3 2 1", "9999 4 0 3 2 1")),
                       "cell 0 has 9999 faces, not 1 to 256");
    }
    SECTION("base64 cut short") {
        std::string text = testkit::slurp(fixtures / "binary-zlib-f64.vtu");
        const std::size_t open = text.find('>', text.find("Name=\"connectivity\"")) + 1;
        const std::size_t close = text.find("</DataArray>", open);
        const std::string data = text.substr(open, close - open);
        const std::size_t keep = data.find_first_not_of(" \n") + 40;
        text.replace(open, close - open, data.substr(0, keep));
        check_one_line(refusal(text), "<DataArray Name=\"connectivity\"> (of 14 point indices");
        CHECK_THAT(refusal(text), Catch::Contains("cut short"));
    }
    SECTION("a zlib bomb") {
        // Cell array "a" of 4 Float64 (32 bytes): one block whose 20-odd
        // bytes inflate to 1 MiB. The header is honest about the block's
        // size but not about what it holds: zlib stops at the 32 bytes.
        const std::string inflated(1 << 20, '\0');
        uLongf size = compressBound(static_cast<uLong>(inflated.size()));
        std::string bomb(size, '\0');
        REQUIRE(compress2(reinterpret_cast<Bytef*>(bomb.data()), &size, reinterpret_cast<const Bytef*>(inflated.data()),
                          static_cast<uLong>(inflated.size()), 9) == Z_OK);
        bomb.resize(size);
        const std::uint64_t words[] = {1, 32, 0, bomb.size()};
        std::string header(sizeof words, '\0');
        std::memcpy(header.data(), words, sizeof words);
        std::string text = testkit::slurp(fixtures / "binary-zlib-f64.vtu");
        const std::size_t open = text.find('>', text.find("Name=\"a\"")) + 1;
        const std::size_t close = text.find("</DataArray>", open);
        text.replace(open, close - open, base64(header) + base64(bomb));
        const std::string m = refusal(text);
        check_one_line(m, "<CellData> <DataArray Name=\"a\">");
        CHECK_THAT(m, Catch::Contains("zlib makes of 32 bytes"));  // refused before inflating at all
        // One that would inflate within zlib's bound for its block: stopped at the block's size.
        const std::string small_inflated(2000, '\0');
        uLongf small_size = compressBound(2000);
        std::string small(small_size, '\0');
        REQUIRE(compress2(reinterpret_cast<Bytef*>(small.data()), &small_size,
                          reinterpret_cast<const Bytef*>(small_inflated.data()), 2000, 9) == Z_OK);
        small.resize(small_size);
        REQUIRE(small.size() <= compressBound(32));
        const std::uint64_t small_words[] = {1, 32, 0, small.size()};
        std::memcpy(header.data(), small_words, sizeof small_words);
        std::string text2 = testkit::slurp(fixtures / "binary-zlib-f64.vtu");
        const std::size_t open2 = text2.find('>', text2.find("Name=\"a\"")) + 1;
        text2.replace(open2, text2.find("</DataArray>", open2) - open2, base64(header) + base64(small));
        check_one_line(refusal(text2), "<CellData> <DataArray Name=\"a\">: a compressed block does not inflate to its size");
    }
    SECTION("the file as a whole") {
        check_one_line(refusal("<VTKFile type=\"ImageData\"/>"), "<VTKFile type> is \"ImageData\", not UnstructuredGrid");
        check_one_line(refusal("<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece"), "not well-formed XML");
        check_one_line(refusal(edited("ascii-f32.vtu", "</Piece>", "</Piece><Piece/>")), "more than one <Piece>");
        check_one_line(refusal(edited("ascii-f32.vtu", "type=\"Float32\" Name=\"b\"", "type=\"Int32\" Name=\"b\"")),
                       "<CellData> <DataArray Name=\"b\"> is type \"Int32\": figgen reads Float32 and Float64 there");
    }
}

TEST_CASE("a mesh written reads back to the same bits", "[vtu]") {
    for (const char* file : {"ascii-f32.vtu", "binary-zlib-f64.vtu", "appended-raw-f64-int32.vtu", "polyhedra-ascii.vtu"}) {
        INFO(file);
        const UnstructuredGrid g = ready::vtu::read_vtu(testkit::slurp(fixtures / file));
        const std::string written = ready::vtu::write_vtu(g);
        const UnstructuredGrid again = ready::vtu::read_vtu(written);
        check_same(g, again);
        CHECK(ready::vtu::write_vtu(again) == written);
        CHECK_THAT(written, Catch::Contains("header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\""));
    }
    // Float64 points, and values no float holds.
    UnstructuredGrid g = ready::vtu::read_vtu(testkit::slurp(fixtures / "binary-zlib-f64.vtu"));
    g.mesh.points[4] = 0.1;
    g.cell_data[1].values[2] = 1.0 / 3.0;
    g.points_float64 = true;
    // A name that, unescaped, would end its element and start another.
    g.cell_data[2].name = "v\"/><DataArray x=\"&amp;";
    check_same(g, ready::vtu::read_vtu(ready::vtu::write_vtu(g)));
    // What it refuses to write.
    UnstructuredGrid bad = g;
    bad.cell_data[0].values.pop_back();
    CHECK_THROWS_AS(ready::vtu::write_vtu(bad), std::invalid_argument);
    bad = g;
    bad.mesh.point_ids[0] = 8;
    CHECK_THROWS_AS(ready::vtu::write_vtu(bad), std::invalid_argument);
    bad = g;
    bad.rd = "<RD/><RD/>";
    CHECK_THROWS_AS(ready::vtu::write_vtu(bad), std::invalid_argument);
}

TEST_CASE("VTK reads the mesh figgen writes as Ready reads it", "[vtu]") {
    const fs::path out = testkit::fresh_dir("vtu-written");
    for (const char* file : {"binary-zlib-f64.vtu", "polyhedra-ascii.vtu"}) {
        INFO(file);
        const UnstructuredGrid g = ready::vtu::read_vtu(testkit::slurp(fixtures / file));
        const fs::path written = out / (std::string("written-") + file);
        testkit::spill(written, ready::vtu::write_vtu(g));
        // VTK's reader, and Ready's look-up of <RD> in the parser's tree
        // (IO_XML.cpp: RD_XMLUnstructuredGridReader::GetRDElement, GetType).
        const std::string script =
            "import json, vtkmodules.all as v\n"
            "r = v.vtkXMLUnstructuredGridReader(); r.SetFileName('" + written.string() + "'); r.Update()\n"
            "assert r.GetErrorCode() == 0\n"
            "g = r.GetOutput(); ids = v.vtkIdList()\n"
            "cells = []\n"
            "for c in range(g.GetNumberOfCells()):\n"
            "    g.GetCellPoints(c, ids); cells.append([ids.GetId(i) for i in range(ids.GetNumberOfIds())])\n"
            "faces = []\n"
            "for c in range(g.GetNumberOfCells()):\n"
            "    if g.GetCellType(c) == 42:\n"
            "        g.GetFaceStream(c, ids); faces += [ids.GetId(i) for i in range(ids.GetNumberOfIds())]\n"
            "d = g.GetCellData()\n"
            "arrays = {d.GetArrayName(i): [d.GetArray(i).GetDataTypeAsString(), d.GetArray(i).GetNumberOfComponents(),\n"
            "          [d.GetArray(i).GetComponent(t, k) for t in range(g.GetNumberOfCells())\n"
            "           for k in range(d.GetArray(i).GetNumberOfComponents())]] for i in range(d.GetNumberOfArrays())}\n"
            "rd = r.GetXMLParser().GetRootElement().FindNestedElementWithName('RD')\n"
            "print(json.dumps({'points': [c for p in range(g.GetNumberOfPoints()) for c in g.GetPoint(p)],\n"
            "                  'cells': cells, 'types': [g.GetCellType(c) for c in range(g.GetNumberOfCells())],\n"
            "                  'faces': faces, 'arrays': arrays,\n"
            "                  'rule': rd.FindNestedElementWithName('rule').GetAttribute('type') if rd else None}))\n";
        testkit::spill(out / "read.py", script);
        const auto vtk = testkit::run_command("/usr/bin/python3 " + (out / "read.py").string());
        INFO(vtk.output);
        REQUIRE(vtk.status == 0);
        const auto j = nlohmann::json::parse(vtk.output);
        CHECK(j["points"].get<std::vector<double>>() == g.mesh.points);
        std::vector<std::vector<std::int64_t>> cells;
        for (std::size_t c = 0; c < g.mesh.cell_count(); ++c)
            cells.emplace_back(g.mesh.point_ids.begin() + g.mesh.offsets[c], g.mesh.point_ids.begin() + g.mesh.offsets[c + 1]);
        CHECK(j["cells"].get<std::vector<std::vector<std::int64_t>>>() == cells);
        CHECK(j["types"].get<std::vector<int>>() == std::vector<int>(g.mesh.types.begin(), g.mesh.types.end()));
        CHECK(j["faces"].get<std::vector<std::int64_t>>() == g.mesh.faces);
        REQUIRE(j["arrays"].size() == g.cell_data.size());
        for (const auto& a : g.cell_data) {
            const auto& got = j["arrays"][a.name];
            CHECK(got[0] == (a.float64 ? "double" : "float"));
            CHECK(got[1] == a.components);
            CHECK(got[2].get<std::vector<double>>() == a.values);
        }
        CHECK(j["rule"] == "formula");
    }
}
