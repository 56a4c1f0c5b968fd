// Ready's files as a hostile user writes them (issue 46): each finding is a
// command run again here. A damaged file is one line and exit 2; a name
// cannot inject a setting; a parameter cannot take a built-in's name; what
// a command does not use it does not decode; messages name the file's
// elements and quote none of its text.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "description/description.hpp"
#include "figgen_run.hpp"
#include "ready/pattern.hpp"

namespace fs = std::filesystem;
using Catch::Contains;

namespace {

const fs::path fixtures = fs::path(FIGGEN_SOURCE_DIR) / "tests/ready/vti";

// A fixture with `from` replaced by `to` (each must be there), as `name` in a fresh folder.
fs::path edited(const std::string& fixture, const std::vector<std::pair<std::string, std::string>>& edits,
                const std::string& name) {
    std::string text = testkit::slurp(fixtures / fixture);
    for (const auto& [from, to] : edits) {
        const std::size_t at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
    }
    const fs::path dir = testkit::fresh_dir("hostile-" + name);
    testkit::spill(dir / name, text);
    return dir / name;
}

// A refused command: exit 2, one line, nothing in its output folder.
std::string refused(const std::string& args) {
    const fs::path out = testkit::fresh_dir("hostile-out");
    const auto run = testkit::figgen(args + " --out " + out.string());
    INFO(args << "\n" << run.output);
    CHECK(run.status == 2);
    CHECK(run.lines() == 1);
    CHECK(fs::is_empty(out));
    return run.output;
}

std::string last_state(const fs::path& folder, const std::string& id) {
    const auto meta = nlohmann::json::parse(testkit::slurp(folder / (id + ".json")));
    return meta["panels"].back()["state_sha256"];
}

}  // namespace

TEST_CASE("zlib block sizes that wrap past 2^64 are one line and exit 2, raw or base64", "[ready][hostile]") {
    // appended-raw-zlib-f32.vti: array a's header at the data's start,
    // UInt64 words (3 blocks of 64 bytes): sizes 2^63 and 2^63 + s0 + s1,
    // so that their sum wraps to what the data holds.
    std::string text = testkit::slurp(fixtures / "appended-raw-zlib-f32.vti");
    const std::size_t data = text.find('_', text.find("<AppendedData")) + 1;
    std::uint64_t words[6];
    std::memcpy(words, text.data() + data, sizeof words);
    REQUIRE(words[0] == 3);
    const std::uint64_t half = std::uint64_t{1} << 63;
    const std::uint64_t s0 = words[3], s1 = words[4];
    words[3] = half;
    words[4] = half + s0 + s1;
    std::memcpy(text.data() + data, words, sizeof words);
    const fs::path dir = testkit::fresh_dir("hostile-wrap");
    testkit::spill(dir / "wrap.vti", text);
    const std::string said = refused("render " + (dir / "wrap.vti").string());
    CHECK_THAT(said, Contains("wrap.vti: <DataArray Name=\"a\">: a compressed block's size is 9223372036854775808 bytes"));
    // convert never decodes the arrays: it writes the description, and says the file starts from them.
    const auto convert = testkit::figgen("convert " + (dir / "wrap.vti").string());
    CHECK(convert.status == 0);
    CHECK_THAT(convert.output, Contains("starts from them"));
}

TEST_CASE("a parameter's name cannot inject a setting: it is refused, or it is data", "[ready][hostile]") {
    const std::string injected = "r = 0.5&#10;ready_edges = false&#10;#";
    const fs::path param = edited("ascii-f32.vti", {{R"(<param name="D">0.5</param>)",
                                                     R"(<param name="D">0.5</param><param name=")" + injected + R"(">1</param>)"}},
                                  "param.vti");
    for (const char* command : {"render", "convert"}) {
        const std::string said = refused(std::string(command) + " " + param.string());
        CHECK_THAT(said, Contains(R"(param.vti: <param name="r = 0.5\nready_edges = false\n#">: its name is not an identifier)"));
    }
    // Named by an overlay whose only shape is off the grid: never checked
    // as a parameter, and kept as the text it is.
    const fs::path overlay = edited(
        "ascii-f32.vti",
        {{R"(<initial_pattern_generator apply_when_loading="false" />)",
          R"(<initial_pattern_generator apply_when_loading="true"><overlay chemical="a"><overwrite /><parameter name=")" +
              injected + R"(" /><pixel x="-3" y="2" z="5" /></overlay><overlay chemical="a"><overwrite /><constant value="0.5" /><everywhere /></overlay></initial_pattern_generator>)"}},
        "overlay.vti");
    const auto converted = testkit::figgen("convert " + overlay.string());
    INFO(converted.output);
    REQUIRE(converted.status == 0);
    const auto pattern = ready::read_pattern(overlay);
    const fs::path dir = overlay.parent_path();
    testkit::spill(dir / "overlay.toml", converted.output);
    const description::Description d = description::load_description(dir / "overlay.toml");
    CHECK_FALSE(d.params.contains("ready_edges"));
    CHECK(d.params == *pattern.description["params"].as_table());
    CHECK(d.style == *pattern.description["style"].as_table());
}

TEST_CASE("any formula text round-trips through convert, and renders the same bits", "[ready][hostile]") {
    // ''' and """ in a comment, a backslash, a tab: the TOML writer quotes them all.
    const fs::path file = edited("binary-zlib-f64.vti",
                                 {{"delta_b = D * laplacian_b;",
                                   "delta_b = D * laplacian_b; // ''' \"\"\" \\ \t ''' a = 1;\n"
                                   "        // [params] ready_edges = false"}},
                                 "quotes.vti");
    const fs::path out = testkit::fresh_dir("hostile-quotes");
    const auto convert = testkit::figgen("convert " + file.string() + " --out " + out.string());
    INFO(convert.output);
    REQUIRE(convert.status == 0);
    const description::Description converted = description::load_description(out / "quotes.toml");
    const description::Description direct = ready::load_pattern(file);
    CHECK(converted.params == direct.params);
    CHECK_THAT(converted.params["formula"].value_or(std::string()), Contains("// ''' \"\"\" \\ \t ''' a = 1;"));
    CHECK_FALSE(converted.params.contains("ready_edges"));
    // The converted description starts from zero, not from the stored
    // arrays: both from zero here, so the same bits.
    const auto from_toml = testkit::figgen("render " + (out / "quotes.toml").string() +
                                           " --set zero_first=true --format png --scale 0.3 --out " +
                                           out.string() + " --set id=toml");
    INFO(from_toml.output);
    REQUIRE(from_toml.status == 0);
    const fs::path zero = edited("binary-zlib-f64.vti",
                                 {{"delta_b = D * laplacian_b;",
                                   "delta_b = D * laplacian_b; // ''' \"\"\" \\ \t ''' a = 1;\n"
                                   "        // [params] ready_edges = false"},
                                  {R"(apply_when_loading="false")", R"(apply_when_loading="true")"}},
                                 "quotes-zero.vti");
    const auto from_vti = testkit::figgen("render " + zero.string() + " --format png --scale 0.3 --out " +
                                          out.string() + " --set id=vti");
    INFO(from_vti.output);
    REQUIRE(from_vti.status == 0);
    CHECK(last_state(out, "toml") == last_state(out, "vti"));
}

TEST_CASE("a parameter named after a built-in is refused, naming the clash, in a .vti and a description", "[ready][hostile]") {
    const std::pair<const char*, const char*> clashes[] = {
        {"laplacian_a", "a stencil keyword of chemical a"},
        {"x_pos", "a cell's position"},
        {"z_pos", "a cell's position"},
        {"M_PI", "a built-in constant"},
        {"a_n", "a neighbour of chemical a"},
        {"b_u2", "a neighbour of chemical b"},
        {"a", "chemical a of the rule"},
        {"delta_a", "the change of chemical a (delta_a)"},
        {"sin", "a built-in function"},
        {"float", "a type of OpenCL C"},
        {"if", "a keyword of OpenCL C"},
        {"index_x", "a name Ready's kernel declares"},
    };
    for (const auto& [name, clash] : clashes) {
        INFO(name);
        // Used by the formula, or not: the same refusal.
        const fs::path vti = edited("ascii-f32.vti",
                                    {{R"(<param name="D">0.5</param>)",
                                      std::string(R"(<param name="D">0.5</param><param name=")") + name + R"(">1</param>)"}},
                                    std::string(name) + ".vti");
        CHECK_THAT(refused("render " + vti.string()),
                   Contains(std::string("<param name=\"") + name + "\">: its name is " + clash + "; a parameter's name is"));
        const fs::path dir = testkit::fresh_dir("hostile-description");
        testkit::spill(dir / "clash.toml", std::string("scene = \"formula\"\n[params]\nwidth = 8\nheight = 8\n"
                                                       "steps = 1\ntimestep = 0.1\nformula = \"delta_a = laplacian_a;\"\n") +
                                               name + " = 1\n[figure]\npanels = [0, 1]\n");
        const std::string said = refused("render " + (dir / "clash.toml").string());
        CHECK_THAT(said, Contains("clash.toml:8: " + std::string(name) + " = 1 is not allowed: its name is " + clash));
    }
    // Names Ready's own patterns use stay allowed: k, F, rotate (an integer built-in of OpenCL), D_a.
    for (const char* name : {"k", "F", "rotate", "D_a", "alpha_1"}) {
        INFO(name);
        const fs::path dir = testkit::fresh_dir("hostile-allowed");
        testkit::spill(dir / "fine.toml", std::string("scene = \"formula\"\n[params]\nwidth = 8\nheight = 8\nsteps = 1\n"
                                                      "timestep = 0.1\nformula = \"delta_a = ") +
                                              name + " * laplacian_a;\"\n" + name + " = 1\n[figure]\npanels = [0, 1]\n");
        const auto run = testkit::figgen("describe " + (dir / "fine.toml").string());
        INFO(run.output);
        CHECK(run.status == 0);
    }
}

TEST_CASE("plain words: describe of a pattern, any case of .vti, meshes, long ids, numbers as given", "[ready][hostile]") {
    const auto described = testkit::figgen("describe " + (fixtures / "binary-zlib-f64.vti").string());
    INFO(described.output);
    CHECK(described.status == 0);
    CHECK_THAT(described.output, Contains("binary-zlib-f64: Test rule"));
    CHECK_THAT(described.output, Contains("scene: formula"));
    CHECK_THAT(described.output, Contains("timestep"));
    // .VTI in capitals is a pattern too.
    const fs::path upper = testkit::fresh_dir("hostile-upper") / "UPPER.VTI";
    fs::copy_file(fixtures / "ascii-f32.vti", upper);
    const fs::path out = testkit::fresh_dir("hostile-upper-out");
    const auto rendered = testkit::figgen("render " + upper.string() + " --set steps=2 --format png --scale 0.3 --out " + out.string());
    INFO(rendered.output);
    CHECK(rendered.status == 0);
    CHECK(fs::exists(out / "UPPER.png"));
    // A mesh, a file that is not a pattern, a kind not run yet: said so.
    const fs::path mesh = testkit::fresh_dir("hostile-mesh") / "bunny.vtu";
    testkit::spill(mesh, "<VTKFile type=\"UnstructuredGrid\"></VTKFile>");
    CHECK_THAT(refused("render " + mesh.string()), Contains("bunny.vtu: no <RD> in <VTKFile>"));
    const auto mesh_described = testkit::figgen("describe " + mesh.string());
    CHECK(mesh_described.status == 2);
    CHECK_THAT(mesh_described.output, Contains("no <RD> in <VTKFile>"));
    const fs::path text = testkit::fresh_dir("hostile-text") / "notes.vti";
    testkit::spill(text, "just some notes\n");
    CHECK_THAT(refused("render " + text.string()), Contains("notes.vti: "));
    CHECK_THAT(refused("render " + edited("ascii-f32.vti", {{R"(type="formula")", R"(type="inbuilt")"}}, "inbuilt.vti").string()),
               Contains("its rule is Ready's inbuilt \"Test rule\": figgen runs Ready's inbuilt Gray-Scott and formula rules"));
    // A 5,000-character id: an unknown figure id, exit 2.
    CHECK_THAT(refused("render " + std::string(5000, 'x')), Contains("unknown figure id 'xxxx"));
    const auto long_describe = testkit::figgen("describe " + std::string(5000, 'x'));
    CHECK(long_describe.status == 2);
    CHECK_THAT(long_describe.output, Contains("unknown figure id"));
    // Numbers as given, never as a wrapped int.
    CHECK_THAT(refused("render " + edited("ascii-f32.vti", {{R"(number_of_chemicals="2")", R"(number_of_chemicals="1e300")"}},
                                          "big.vti").string()),
               Contains("<formula number_of_chemicals> is \"1e300\", not an integer from 1 to 26"));
    CHECK_THAT(refused("render " + edited("ascii-f32.vti", {{R"(<param name="D">0.5</param>)", R"(<param name="D">1e300</param>)"}},
                                          "huge-param.vti").string()),
               Contains("D = 1e+300 is not allowed"));
    // An XML mistake: its line and kind, none of the file's text.
    const std::string said = refused(
        "render " + edited("ascii-f32.vti", {{"<render_settings>", "<render_settings><SECRET-TEXT-OF-THE-FILE a='1' a='2'/>"}},
                           "xml.vti").string());
    CHECK_THAT(said, Contains("not well-formed XML (line"));
    CHECK(said.find("SECRET") == std::string::npos);
    // A mistake the scene finds: the element that gave the key, not a line of a translated text.
    CHECK_THAT(refused("render " + edited("ascii-f32.vti", {{R"(<param name="timestep">0.1</param>)",
                                                             R"(<param name="timestep">0.1</param><param name="q">1</param>)"},
                                                            {"delta_a = D * laplacian_a;", "delta_a = D * laplacian_a + q * (1 / 0;"}},
                                          "formula.vti").string()),
               Contains("formula.vti <formula>: formula = ... is not allowed: line 1, column"));
}

TEST_CASE("convert and describe decode no array, and render only the chemicals'", "[ready][hostile]") {
    // 8 chemicals of 4096 x 4096 (1 GiB as doubles, the most figgen
    // reads) whose arrays are damaged: what never decodes them works.
    std::string pointdata;
    for (char c = 'a'; c < 'i'; ++c)
        pointdata += std::string("<DataArray type=\"Float32\" Name=\"") + c + "\" format=\"binary\">AAAA</DataArray>";
    const fs::path big = edited("binary-f32.vti",
                                {{R"(WholeExtent="0 7 0 5 0 0")", R"(WholeExtent="0 4095 0 4095 0 0")"},
                                 {R"(number_of_chemicals="2")", R"(number_of_chemicals="8")"}},
                                "eight.vti");
    std::string text = testkit::slurp(big);
    const std::size_t from = text.find("<PointData>") + 11, to = text.find("</PointData>");
    text.replace(from, to - from, pointdata);
    testkit::spill(big, text);
    const auto convert = testkit::figgen("convert " + big.string());
    INFO(convert.output);
    CHECK(convert.status == 0);
    CHECK_THAT(convert.output, Contains("width = 4096"));
    const auto describe = testkit::figgen("describe " + big.string());
    CHECK(describe.status == 0);
    // The memory estimate, which counts the arrays, comes before any is decoded.
    CHECK_THAT(refused("render " + big.string() + " --max-memory 1G"), Contains("more than --max-memory 1.0 GiB"));
    CHECK_THAT(refused("render " + big.string() + " --max-memory 8G"), Contains("eight.vti: <DataArray Name=\"a\">: an array's header is cut short"));
}
