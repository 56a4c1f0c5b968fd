// What a gallery card says: its key results against the figure's JSON, the
// figures of other descriptions, and metadata written by hand or by someone
// else (untrusted: escaped, never a crash).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "figgen_run.hpp"

namespace fs = std::filesystem;

namespace {

// One value cell of a card's key-results table, as the page has it.
struct KeyCell {
    std::string label, path, kind, error_path, text, reference;
};

std::string unescaped(std::string text) {
    for (const auto& [entity, c] : std::vector<std::pair<std::string, std::string>>{
             {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&#39;", "'"}, {"&amp;", "&"}}) {
        for (auto at = text.find(entity); at != std::string::npos; at = text.find(entity, at + c.size()))
            text.replace(at, entity.size(), c);
    }
    return text;
}

// Each card's key results, by figure id, read from the written HTML.
std::map<std::string, std::vector<KeyCell>> key_cells(const std::string& page) {
    std::map<std::string, std::vector<KeyCell>> cards;
    const std::regex article("<article id=\"([^\"]+)\">([\\s\\S]*?)</article>");
    const std::regex row("<tr><th scope=\"row\">([^<]*)</th><td data-path=\"([^\"]*)\" data-kind=\"([^\"]*)\""
                         "(?: data-error-path=\"([^\"]*)\")?>([^<]*)</td>"
                         "(?:<td class=\"reference\"(?: rowspan=\"[0-9]+\")?>([^<]*)</td>)?</tr>");
    for (std::sregex_iterator a(page.begin(), page.end(), article), end; a != end; ++a) {
        const std::string body = (*a)[2];
        std::vector<KeyCell>& cells = cards[unescaped((*a)[1])];
        for (std::sregex_iterator r(body.begin(), body.end(), row); r != end; ++r)
            cells.push_back({unescaped((*r)[1]), unescaped((*r)[2]), (*r)[3], unescaped((*r)[4]), unescaped((*r)[5]),
                             unescaped((*r)[6])});
    }
    return cards;
}

// The numbers in a cell's text, in order ("0.5927 ± 0.0003" -> 0.5927, 0.0003).
std::vector<double> numbers_in(const std::string& text) {
    std::vector<double> numbers;
    const std::regex number("-?[0-9]+(\\.[0-9]+)?(e[-+][0-9]+)?");
    for (std::sregex_iterator n(text.begin(), text.end(), number), end; n != end; ++n)
        numbers.push_back(std::strtod(n->str().c_str(), nullptr));
    return numbers;
}

// `shown` is `exact` to the 4 significant digits a card gives.
bool agrees(double shown, double exact) {
    if (exact == 0) return shown == 0;
    const double unit = std::pow(10.0, std::floor(std::log10(std::abs(exact))) - 3);
    return std::abs(shown - exact) <= 0.5 * unit * 1.000001;
}

nlohmann::json read_json(const fs::path& file) { return nlohmann::json::parse(testkit::slurp(file)); }

// Every key-result cell of `id`'s card against the value its data-path
// names in `id`.json.
void check_against_json(const std::vector<KeyCell>& cells, const nlohmann::json& meta) {
    for (const KeyCell& cell : cells) {
        INFO(cell.label << " = " << cell.text << " (" << cell.path << ", " << cell.kind << ")");
        const nlohmann::json& value = meta.at(nlohmann::json::json_pointer(cell.path));
        const std::vector<double> shown = numbers_in(cell.text);
        REQUIRE_FALSE(shown.empty());
        if (cell.kind == "count") {
            CHECK(shown[0] == double(value.size()));
        } else if (cell.kind == "integer") {
            CHECK(shown[0] == value.get<double>());
        } else if (cell.kind == "range") {  // first to last
            REQUIRE(shown.size() >= 2);
            CHECK(agrees(shown[0], value.front().get<double>()));
            CHECK(agrees(shown[1], value.back().get<double>()));
        } else if (cell.kind == "bounds") {  // x xmin to xmax, y ymin to ymax
            REQUIRE(shown.size() >= 4);
            for (int i = 0; i < 4; ++i) CHECK(agrees(shown[i], value[i].get<double>()));
        } else if (!cell.error_path.empty()) {
            // value ± error: the error to 2 significant digits, the value to the same decimal.
            const double error = meta.at(nlohmann::json::json_pointer(cell.error_path)).get<double>();
            REQUIRE(shown.size() >= 2);
            CHECK(std::abs(shown[1] - error) <= 0.05 * error);
            CHECK(std::abs(shown[0] - value.get<double>()) <= 0.05 * error);
        } else {
            CHECK(cell.kind == "number");
            CHECK(agrees(shown[0], value.get<double>()));
        }
    }
}

const KeyCell* find_label(const std::vector<KeyCell>& cells, const std::string& label) {
    for (const KeyCell& cell : cells)
        if (cell.label == label) return &cell;
    return nullptr;
}

}  // namespace

TEST_CASE("gallery key numbers agree with each figure's JSON and stand beside the catalog's references",
          "[gallery][cli]") {
    const fs::path out = testkit::fresh_dir("gallery-numbers");
    const testkit::Run rendered =
        testkit::figgen("render tc7-7 tc7-9 sf87-dim pl-phyllotaxis --no-video --scale 0.5 --out " + out.string());
    INFO(rendered.output);
    REQUIRE(rendered.status == 0);
    REQUIRE(testkit::figgen("gallery --out " + out.string()).status == 0);
    const auto cards = key_cells(testkit::slurp(out / "index.html"));
    for (const std::string id : {"tc7-7", "tc7-9", "sf87-dim", "pl-phyllotaxis"}) {
        INFO(id);
        REQUIRE(cards.count(id) == 1);
        REQUIRE(cards.at(id).size() >= 2);
        check_against_json(cards.at(id), read_json(out / (id + ".json")));
    }
    // The numbers the catalog gives a reference for, with it.
    const auto& counts = cards.at("tc7-7");
    const KeyCell* rule18 = find_label(counts, "slope, rule 18");
    REQUIRE(rule18 != nullptr);
    CHECK(rule18->path == "/panels/2/slope");
    CHECK_THAT(rule18->reference, Catch::Contains("1.57") && Catch::Contains("1.585"));
    REQUIRE(find_label(counts, "slope, rule 20") != nullptr);
    CHECK_THAT(find_label(counts, "slope, rule 20")->reference, Catch::Contains("1.01"));
    const KeyCell* scaling = find_label(cards.at("tc7-9"), "slope (fractal dimension)");
    REQUIRE(scaling != nullptr);
    CHECK(scaling->path == "/slope");
    CHECK_THAT(scaling->reference, Catch::Contains("1.85") && Catch::Contains("1.896"));
    const KeyCell* fit = find_label(cards.at("sf87-dim"), "fit range l, 0101010");
    REQUIRE(fit != nullptr);
    CHECK(fit->kind == "range");
    const KeyCell* golden = find_label(cards.at("pl-phyllotaxis"), "divergence angle, panel 1");
    REQUIRE(golden != nullptr);
    CHECK_THAT(golden->reference, Catch::Contains("137.508"));
    // The full JSON stays one link away.
    CHECK_THAT(testkit::slurp(out / "index.html"), Catch::Contains("<a href=\"tc7-9.json\">metadata</a>"));
}

TEST_CASE("gallery shows figures of descriptions outside the catalog after the catalog's", "[gallery][cli]") {
    const fs::path out = testkit::fresh_dir("gallery-others");
    const fs::path mine = out / "descriptions";
    fs::create_directories(mine);
    // A figure of the user's own: tc7-9's scene under another id.
    std::string text = testkit::slurp(fs::path(FIGGEN_SOURCE_DIR) / "figures" / "tc7-9.toml");
    text = std::regex_replace(text, std::regex("id *= *\"tc7-9\""), "id = \"my-scaling\"");
    testkit::spill(mine / "my-scaling.toml", text);
    const testkit::Run rendered = testkit::figgen("render tc7-7 " + (mine / "my-scaling.toml").string() +
                                                  " --no-video --scale 0.5 --out " + out.string());
    INFO(rendered.output);
    REQUIRE(rendered.status == 0);
    // Files that are not figgen's figures: a JSON of another program, one
    // without its PNG, one whose id is not its name, and a symlink.
    testkit::spill(out / "package.json", "{\"name\": \"x\", \"version\": \"1.0\"}");
    fs::copy_file(out / "tc7-7.png", out / "package.png");
    nlohmann::json meta = read_json(out / "my-scaling.json");
    testkit::spill(out / "lonely.json", meta.dump());
    meta["id"] = "someone-else";
    testkit::spill(out / "renamed.json", meta.dump());
    fs::copy_file(out / "tc7-7.png", out / "renamed.png");
    fs::create_symlink("my-scaling.json", out / "linked.json");
    fs::copy_file(out / "tc7-7.png", out / "linked.png");

    const testkit::Run run = testkit::figgen("gallery --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK_THAT(run.output, Catch::Contains("index.html: 2 figures"));
    const std::string page = testkit::slurp(out / "index.html");
    CHECK_THAT(page, Catch::Contains("2 figures rendered by figgen") && Catch::Contains("(1 from descriptions outside it)"));
    const auto catalog_card = page.find("<article id=\"tc7-7\">"), own_card = page.find("<article id=\"my-scaling\">");
    REQUIRE(catalog_card != std::string::npos);
    REQUIRE(own_card != std::string::npos);
    CHECK(catalog_card < own_card);
    CHECK(fs::exists(out / "thumbs" / "my-scaling.png"));
    for (const std::string other : {"package", "lonely", "renamed", "linked", "someone-else"})
        CHECK(page.find("<article id=\"" + other + "\"") == std::string::npos);
    // Its key numbers come from its scene, checked against its JSON as the catalog's are.
    const auto cards = key_cells(page);
    REQUIRE(cards.at("my-scaling").size() >= 2);
    check_against_json(cards.at("my-scaling"), read_json(out / "my-scaling.json"));
}

TEST_CASE("gallery escapes hostile metadata and survives JSON that lies", "[gallery][cli]") {
    const fs::path out = testkit::fresh_dir("gallery-hostile");
    const testkit::Run rendered = testkit::figgen("render tc7-7 tc7-5 --scale 0.5 --out " + out.string());
    INFO(rendered.output);
    REQUIRE(rendered.status == 0);
    // A foreign figure: figgen's fields, every string an attack, numbers
    // where strings go and strings where numbers go, a film that promises
    // frames it does not have.
    nlohmann::json meta = read_json(out / "tc7-7.json");
    const std::string attack = "<script>alert('x')</script>\"><img src=x onerror=alert(1)>&amp;";
    meta["id"] = "evil";
    meta["title"] = attack;
    meta["source"] = attack;
    meta["caption"] = attack;
    meta["params"]["rules"] = attack;
    meta["style"][attack] = attack;
    meta["panels"][0]["rule"] = "<b onmouseover=alert(1)>";
    meta["panels"][1]["slope"] = attack;
    meta["panels"][2]["slope"] = nullptr;
    meta["panels"].push_back({{"rule", 1e308}, {"slope", -1e308}});
    meta["animation"] = {{"frames", 999999}, {"fps", 10}, {"size", {120, 130}}, {"poster", {{"frame", attack}}}};
    testkit::spill(out / "evil.json", meta.dump());
    fs::copy_file(out / "tc7-7.png", out / "evil.png");
    fs::copy_file(out / "tc7-5.mp4", out / "evil.mp4");
    // One whose poster frame is past the film's end, and not JSON at all.
    nlohmann::json liar = read_json(out / "tc7-5.json");
    liar["id"] = "liar";
    liar["animation"]["poster"]["frame"] = 1 << 30;
    testkit::spill(out / "liar.json", liar.dump());
    fs::copy_file(out / "tc7-5.png", out / "liar.png");
    fs::copy_file(out / "tc7-5.mp4", out / "liar.mp4");
    // Nested a hundred thousand levels deep, where the parameters go: past
    // the gallery's depth limit (64), so refused as it is read.
    std::string deep = read_json(out / "tc7-7.json").dump();
    deep.replace(deep.find("\"id\":\"tc7-7\""), 12, "\"id\":\"deep\"");
    const std::string nest = std::string(100000, '[') + std::string(100000, ']');
    deep.insert(deep.find("\"params\":{") + 10, "\"nested\":" + nest + ",");
    testkit::spill(out / "deep.json", deep);
    fs::copy_file(out / "tc7-7.png", out / "deep.png");
    testkit::spill(out / "broken.json", "{\"id\": \"broken\", \"figgen_version\": ");
    fs::copy_file(out / "tc7-5.png", out / "broken.png");

    const testkit::Run run = testkit::figgen("gallery --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    const std::string page = testkit::slurp(out / "index.html");
    CHECK(page.find("<script") == std::string::npos);
    CHECK(page.find("<img src=x") == std::string::npos);
    CHECK(page.find("<b onmouseover") == std::string::npos);
    CHECK_THAT(page, Catch::Contains("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;&quot;&gt;&lt;img src=x"));
    REQUIRE(page.find("<article id=\"evil\">") != std::string::npos);
    CHECK(page.find("<article id=\"broken\">") == std::string::npos);
    CHECK(page.find("<article id=\"deep\">") == std::string::npos);
    CHECK_THAT(page, Catch::Contains("could not show deep: deep.json nests arrays and objects more than 64 deep"));
    // The honest slope is shown under its hostile label; the string and
    // the null are not numbers and are left out.
    const auto cards = key_cells(page);
    const std::vector<KeyCell>& evil = cards.at("evil");
    CHECK(find_label(evil, "slope, rule <b onmouseover=alert(1)>") != nullptr);
    for (const KeyCell& cell : evil) CHECK(cell.path != "/panels/1/slope");
    for (const KeyCell& cell : evil) CHECK(cell.path != "/panels/2/slope");
    // The lying films: a video without a poster that cannot be decoded, the
    // out-of-range poster frame read as the last frame.
    CHECK_THAT(page, Catch::Contains("<video controls preload=\"metadata\" src=\"evil.mp4\" width=\"120\""));
    CHECK_FALSE(fs::exists(out / "posters" / "evil.png"));
    const int frames = liar["animation"]["frames"].get<int>();
    CHECK_THAT(page, Catch::Contains("src=\"liar.mp4\" poster=\"posters/liar.png\""));
    CHECK_THAT(page, Catch::Contains("data-poster-frame=\"" + std::to_string(frames - 1) + "\""));
}
