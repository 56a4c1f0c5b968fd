// Titles and captions as someone else might write them, run through the
// figgen command: text that is no UTF-8 refused before anything runs,
// flags that once ended figgen by SIGABRT (libunibreak) drawn, and text
// 100,000 characters long refused in well under the minute it took.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <string>

#include "figgen_run.hpp"

namespace fs = std::filesystem;

namespace {

std::string long_text(std::size_t characters) {
    std::string text;
    while (text.size() < characters) text += "lorem ipsum dolor sit amet ";
    text.resize(characters);
    return text;
}

struct Timed {
    testkit::Run run;
    double seconds;
};

Timed timed_figgen(const std::string& args) {
    const auto start = std::chrono::steady_clock::now();
    testkit::Run run = testkit::figgen(args);
    return {run, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

}  // namespace

TEST_CASE("a title that is no UTF-8 is refused with exit 2, its key and value, and nothing written", "[cli][text]") {
    const fs::path out = testkit::fresh_dir("text-input-refused") / "out";
    // Raw bytes inside the shell's single quotes reach figgen as they are.
    for (const auto& [set, shown] :
         {std::pair<std::string, std::string>{"'title=caf\xC3'", "title = \"caf\\xC3\""},
          {"'title=\xEF\xBF\xBF'", "title = \"\\uFFFF\""},
          {"'figure.panel_title=step \x1B[2J{step}'", "figure.panel_title = \"step \\x1B[2J{step}\""}}) {
        INFO(set);
        const testkit::Run run = testkit::figgen("render tc7-1 --set " + set + " --set figure.caption=title --out " + out.string());
        CHECK(run.status == 2);
        CHECK(run.lines() == 1);
        CHECK(run.output.find(shown + " is not allowed: text of valid UTF-8 characters") != std::string::npos);
        CHECK(run.output.find("step 0") == std::string::npos);  // no progress: nothing ran
        CHECK_FALSE(fs::exists(out));
    }
}

TEST_CASE("flags and tags in a title or original caption drawn as a caption are drawn", "[cli][text]") {
    const fs::path dir = testkit::fresh_dir("text-input-flags");
    // U+1F1FA U+1F1F8 and U+1F1EB U+1F1F7: libunibreak asserted on regional indicators.
    const std::string flags = "\xF0\x9F\x87\xBA\xF0\x9F\x87\xB8 \xF0\x9F\x87\xAB\xF0\x9F\x87\xB7 diffusion";
    const testkit::Run title = testkit::figgen("render tc7-1 --no-video --set 'title=" + flags +
                                               "' --set figure.caption=title --out " + (dir / "a").string());
    CHECK(title.status == 0);
    CHECK(fs::is_regular_file(dir / "a" / "tc7-1.png"));
    testkit::spill(dir / "flag.toml", "id = \"flag\"\nscene = \"diffusion\"\noriginal_caption = \"" + flags +
                                          " \xF3\xA0\x80\x81 tag\"\n[params]\nn = 12\n[figure]\npanels = [0, 3]\n"
                                          "size = [400, 200]\ncaption = \"original\"\n");
    const testkit::Run original = testkit::figgen("render " + (dir / "flag.toml").string() + " --out " + (dir / "b").string());
    CHECK(original.status == 0);
    CHECK(fs::is_regular_file(dir / "b" / "flag.png"));
}

TEST_CASE("100,000 characters of title or caption are refused in seconds, no size beyond the largest suggested",
          "[cli][text]") {
    const fs::path out = testkit::fresh_dir("text-input-long") / "out";
    const std::string text = long_text(100000);
    // As a caption: 882 lines at 900 px would need a figure 46251 px tall.
    const Timed caption = timed_figgen("render tc7-1 --no-video --set 'title=" + text +
                                       "' --set figure.caption=title --out " + out.string());
    CHECK(caption.run.status == 2);
    CHECK(caption.run.lines() == 1);
    CHECK(caption.run.output.find("no size fits them (a figure is at most 16384 x 16384)") != std::string::npos);
    CHECK(caption.run.output.find("--size") == std::string::npos);
    // 64 s before (15 s of CPU), 0.2 s of CPU now; the bound leaves room for a
    // sanitizer build on a loaded machine (the panel title took 11.9 s there).
    CHECK(caption.seconds < 30);
    CHECK_FALSE(fs::exists(out));  // refused before anything ran or was written
    // As a panel title: wider than 8 times the page.
    const Timed panel = timed_figgen("render tc7-1 --no-video --set 'figure.panel_title=" + text + "' --out " + out.string());
    CHECK(panel.run.status == 2);
    CHECK(panel.run.lines() == 1);
    CHECK(panel.run.output.find("no size up to 8 times as large (each side at most 16384) holds them") != std::string::npos);
    CHECK(panel.seconds < 30);  // more than a minute before
    // A caption that fits a larger figure still gets its size: 2,000 characters at 900 x 450.
    const testkit::Run fits = testkit::figgen("render tc7-1 --no-video --set 'title=" + long_text(2000) +
                                              "' --set figure.caption=title --out " + out.string());
    CHECK(fits.status == 2);
    CHECK(fits.output.find("--size 900x") != std::string::npos);
}
