// Issues 17's, 34's and 35's targets side by side, from one `make bench` run: the numbers
// latest.json holds (the book's route, the pipeline) and Google Benchmark's
// run just before (benchmarks.json), each against its target, into
// bench/results/targets.md and latest.json's "targets".
#include <cstdio>
#include <fstream>
#include <string>

#include "accuracy.hpp"
#include "base/atomic_file.hpp"

namespace bench {
namespace {

// The mean items per second of a Google Benchmark run, 0 when absent.
double benchmark_rate(const std::filesystem::path& file, const std::string& name) {
    std::ifstream in(file);
    if (!in) return 0;
    const nlohmann::json runs = nlohmann::json::parse(in, nullptr, false);
    if (runs.is_discarded() || !runs.contains("benchmarks")) return 0;
    for (const auto& run : runs["benchmarks"])
        if (run.value("name", "") == name + "_mean" ||
            (run.value("name", "") == name && !run.contains("aggregate_name")))
            return run.value("items_per_second", 0.0);
    return 0;
}

// A number at `path` (keys) in `json`, 0 when it is not there.
double at(const nlohmann::json& json, std::initializer_list<const char*> path) {
    const nlohmann::json* node = &json;
    for (const char* key : path) {
        if (!node->is_object() || !node->contains(key)) return 0;
        node = &(*node)[key];
    }
    return node->is_number() ? node->get<double>() : 0;
}

// The Gray-Scott formula's cell-updates per second over the float kernel's, 0 when either is absent.
double formula_against_kernel(const Paths& paths) {
    const auto file = paths.results / "benchmarks.json";
    const double kernel = benchmark_rate(file, "gray_scott_kernel<float>/n:256/threads:2/real_time");
    const double formula = benchmark_rate(file, "gray_scott_formula<false>/n:256/threads:2/real_time");
    return kernel > 0 && formula > 0 ? formula / kernel : 0;
}

struct Row {
    std::string what, unit;
    double value;
    double target;
    bool at_least;  // the target is a floor (speed-ups, rates), else a ceiling (seconds)
    std::string elsewhere = {};  // where a row not measured here is measured
};

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, v >= 100 ? "%.0f" : v >= 10 ? "%.1f" : "%.2f", v);
    return text;
}

}  // namespace

nlohmann::json target_table(const nlohmann::json& latest, const Paths& paths) {
    const nlohmann::json& pipe = latest.contains("pipeline") ? latest["pipeline"] : nlohmann::json::object();
    const std::vector<Row> rows = {
        {"nine printed tc7 figures, PNG + JSON, one `figgen render`, speed-up over the book's route", "x",
         at(pipe, {"tc7_printed_figures", "speedup_over_book"}), 30, true},
        {"tc7-2 with its 351-frame film, speed-up over the book reader's film", "x",
         at(pipe, {"tc7_2_film", "speedup_over_book"}), 25, true},
        {"`make figures` from clean, -j2", "s", at(pipe, {"make_figures_from_clean", "seconds"}), 30, false},
        {"tc7-2's film at 1280 x 720, drawing + encoding", "frames/s",
         at(pipe, {"animation_1280x720", "render_and_encode_frames_per_second"}), 60, true},
        {"Gray-Scott float kernel, n = 256, 2 threads", "G cell-updates/s",
         benchmark_rate(paths.results / "benchmarks.json", "gray_scott_kernel<float>/n:256/threads:2/real_time") / 1e9,
         5, true},
        {"gs-atlas", "s", at(pipe, {"gs_atlas", "seconds"}), 12, false},
        {"pc-threshold", "s", at(pipe, {"pc_threshold", "seconds"}), 5, false},
        // Issue 34's: the two of this machine, and the GPU node's, measured
        // by `bash .gpu/run.sh` there (../shared/tools/gpu-bundle).
        {"issue 34: tc7-2 with its film, speed-up over the book reader's film", "x",
         at(pipe, {"tc7_2_film", "speedup_over_book"}), 16, true},
        {"issue 34: `make figures` from clean, program built, against the book's nine-figure route", "x",
         at(pipe, {"make_figures_from_clean", "times_book_nine_figures"}), 2.0, false},
        {"issue 34: 16-core GPU node, tc7-2's film, 151 frames at 3840 x 2160", "frames/s", 0, 30, true,
         "a GPU node: bash .gpu/run.sh"},
        {"issue 34: the same at 1920 x 1080", "frames/s", 0, 120, true, "a GPU node: bash .gpu/run.sh"},
        // Issue 35's: a formula model against the hand-written kernel, same run.
        {"issue 35: Ready's Gray-Scott formula (float, n = 256, 2 threads) against the hand-written float kernel",
         "x", formula_against_kernel(paths), 0.5, true},
    };
    nlohmann::json out = nlohmann::json::array();
    std::string table = "| what | measured | target | met |\n|---|---|---|---|\n";
    for (const Row& r : rows) {
        const bool measured = r.value > 0, met = measured && (r.at_least ? r.value >= r.target : r.value <= r.target);
        out.push_back({{"what", r.what},
                       {"unit", r.unit},
                       {"value", r.value},
                       {"target", r.target},
                       {"at_least", r.at_least},
                       {"met", met}});
        table += "| " + r.what + " | " +
                 (measured ? number(r.value) + " " + r.unit
                           : "not measured" + (r.elsewhere.empty() ? "" : " here (" + r.elsewhere + ")")) +
                 " | " +
                 (r.at_least ? ">= " : "<= ") + number(r.target) + " " + r.unit + " | " +
                 (measured ? (met ? "yes" : "no") : "-") + " |\n";
    }
    base::write_file_atomically(paths.results / "targets.md", table);
    std::printf("%s", table.c_str());
    return out;
}

}  // namespace bench
