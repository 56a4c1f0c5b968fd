#pragma once
// What the studies of `make bench` (figgen_accuracy) share: a wall clock, and
// curves of run time against error for the Pareto figure. Each study returns
// its rows for bench/results/latest.json and adds its curves.

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace bench {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Point {
    double seconds;  // run time of the method at this cost
    double error;    // its error against the known value, > 0 (log axis)
};

struct Curve {
    std::string label;   // legend entry
    std::string colour;  // "#rrggbb"
    std::vector<Point> points;
};

// Which plot of the Pareto figure a curve goes to.
struct Curves {
    std::vector<Curve> numerics;    // a model's arithmetic against an exact solution
    std::vector<Curve> estimators;  // a statistical estimate against a known constant
    // A formula model's integrators (out/bench-integrators.png): against a
    // known answer, and against a fine reference run.
    std::vector<Curve> integrators_known, integrators_reference;
};

// Where the pipeline study finds the project.
struct Paths {
    std::filesystem::path source;   // the project's root (figures/, bench/, out/)
    std::filesystem::path build;    // the CMake build folder
    std::filesystem::path figgen;   // the figgen program
    std::filesystem::path results;  // bench/results
};

// sim studies (accuracy_models.cpp): arithmetic and estimators.
nlohmann::json gray_scott_float_vs_double(Curves& curves);
nlohmann::json diffusion_vs_exact(Curves& curves);
nlohmann::json percolation_threshold(Curves& curves);
nlohmann::json fractal_dimensions(Curves& curves);
nlohmann::json gray_scott_long_run(long long steps);
// A formula model's integrators, each over a range of timesteps
// (accuracy_formula.cpp): the heat equation's Fourier mode against its
// exact decay, Gray-Scott against a fine RK4 run; and the cheapest
// integrator for several errors.
nlohmann::json formula_integrators(Curves& curves);

// The book's route against ours (runs bench/book_peer.py; {"skipped": why}
// without Debian's python3, numpy, scipy or matplotlib), and whole-pipeline
// times, with the book's time for the nine printed figures when `peer` has it
// (accuracy_pipeline.cpp).
nlohmann::json peer_comparison(const Paths& paths);
nlohmann::json pipeline_times(const Paths& paths, const nlohmann::json& peer);
// Films' MP4 bytes and render times at several animation.segment_frames,
// into bench/results/segments.md: what the default length is chosen from.
nlohmann::json segment_lengths(const Paths& paths);

// Issue 17's targets, each against its measured value from this run
// (latest.json so far) and Google Benchmark's benchmarks.json; also written
// to results/targets.md (accuracy_targets.cpp).
nlohmann::json target_table(const nlohmann::json& latest, const Paths& paths);

// x264 presets and tunes on the same drawn frames of two films (tc7-2, bd-500):
// encoding time, file size, SSIM against the drawn frames (FFmpeg's ssim
// filter, the ffmpeg program), and the fastest setting inside issue 17's
// bounds; also written to results/encoder.json and encoder.md
// (accuracy_encoder.cpp).
nlohmann::json encoder_settings(const Paths& paths);

}  // namespace bench
