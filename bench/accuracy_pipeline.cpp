// The book's route against ours, and whole-pipeline times: the Gray-Scott
// step and the percolation runs timed in numpy/scipy (bench/book_peer.py,
// Debian's python3) and here on the same grids; the nine printed tc7 figures
// through matplotlib and through figgen; `make figures` from clean; frames
// per second of a 1280x720 animation.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <stdexcept>

#include "accuracy.hpp"
#include "app/render/frame_canvas.hpp"
#include "media/video.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "sim/gray_scott.hpp"
#include "sim/gray_scott_kernels.hpp"
#include "sim/percolation.hpp"
#include "sim/random.hpp"

namespace bench {
namespace {

// In single quotes for the shell (the project's paths hold no quote).
std::string quoted(const std::filesystem::path& p) {
    std::string s = "'";  // appended, not "'" + ... + "'": GCC 12 warns falsely (-Wrestrict) on that
    s += p.string();
    s += '\'';
    return s;
}

// Runs a shell command and returns its wall time; throws when it fails.
double timed(const std::string& command) {
    const auto t0 = Clock::now();
    const int status = std::system(command.c_str());
    const double t = seconds_since(t0);
    if (status != 0) throw std::runtime_error("command failed (status " + std::to_string(status) + "): " + command);
    return t;
}

std::filesystem::path scratch_dir(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("figgen-bench-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// Seconds per step of `advance` on a grid, over enough steps for ~0.3 s.
template <class Advance>
double seconds_per_step(Advance advance, long long cells) {
    const int steps = int(std::max<long long>(2, 60'000'000 / cells));
    advance(1);  // first touch of the buffers and the thread team
    const auto t0 = Clock::now();
    advance(steps);
    return seconds_since(t0) / steps;
}

// The tc7-2 update on an n x n grid: the model the figures use, and the fast kernels.
nlohmann::json gray_scott_against(const nlohmann::json& peer_row) {
    sim::GrayScottParams p;
    p.n = peer_row.at("n").get<int>();
    sim::Random rng(17);
    sim::GrayScott model(p, rng);
    const long long cells = static_cast<long long>(p.n) * p.n;
    sim::GrayScottKernel<double> twice(p, model.a(), model.b());
    sim::GrayScottKernel<float> single(p, model.a(), model.b());
    const double book = peer_row.at("seconds_per_step").get<double>();
    nlohmann::json row = {{"n", p.n}, {"book_seconds_per_step", book}};
    auto add = [&](const char* name, double seconds) {
        row[std::string(name) + "_seconds_per_step"] = seconds;
        row[std::string(name) + "_speedup_over_book"] = book / seconds;
    };
    add("model_double_1_thread", seconds_per_step(
                                     [&](int s) {
                                         for (int i = 0; i < s; ++i) model.step();
                                     },
                                     cells));
    add("kernel_double_2_threads", seconds_per_step([&](int s) { twice.step(s, 2); }, cells));
    add("kernel_float_2_threads", seconds_per_step([&](int s) { single.step(s, 2); }, cells));
    return row;
}

// The book's test_perc and find_critical at n = 100, as the peer ran them.
nlohmann::json percolation_against(const nlohmann::json& peer) {
    const auto& runs = peer.at("test_perc");
    const int n = runs.at("n").get<int>(), count = 200;
    const double q = runs.at("q").get<double>();
    sim::Random rng(7);
    long long steps = 0;
    auto t0 = Clock::now();
    for (int i = 0; i < count; ++i) {
        sim::Percolation model({n, q}, rng);
        steps += sim::run_to_bottom_or_fixed_point(model).steps;
    }
    const double per_run = seconds_since(t0) / count, book_per_run = runs.at("seconds_per_run").get<double>();

    const auto& walk = peer.at("find_critical");
    const int iterations = walk.at("iterations").get<int>();
    t0 = Clock::now();
    const auto qs = sim::find_critical(walk.at("n").get<int>(), 0.6, 0.005, iterations, rng);
    const double walk_seconds = seconds_since(t0), book_walk = walk.at("seconds").get<double>();
    return {{"test_perc",
             {{"n", n},
              {"q", q},
              {"runs", count},
              {"mean_steps", double(steps) / count},
              {"seconds_per_run", per_run},
              {"book_seconds_per_run", book_per_run},
              {"speedup_over_book", book_per_run / per_run}}},
            {"find_critical",
             {{"n", walk.at("n")},
              {"iterations", iterations},
              {"estimate", std::accumulate(qs.begin(), qs.end(), 0.0) / double(qs.size())},
              {"seconds", walk_seconds},
              {"book_seconds", book_walk},
              {"speedup_over_book", book_walk / walk_seconds}}}};
}

// Render-only and render+encode rates of a 1280x720 Gray-Scott frame (two
// smooth layers, tc7-2's state at step 2000), 120 frames each.
nlohmann::json frames_in_process() {
    sim::GrayScottParams p;
    sim::Random rng(17);
    const sim::GrayScott start(p, rng);
    sim::GrayScottKernel<double> model(p, start.a(), start.b());
    model.step(2000, 0);
    scenes::FieldPanel panel{"step 2000", {}};
    panel.layers.push_back(
        {p.n, p.n, model.a().cells(), {&render::colormap("Reds"), 0, 1, 0.7f, render::Sampling::smooth}});
    panel.layers.push_back(
        {p.n, p.n, model.b().cells(), {&render::colormap("Blues"), 0, 0.5, 0.7f, render::Sampling::smooth}});
    const int frames = 120, width = 1280, height = 720;
    auto t0 = Clock::now();
    for (int i = 0; i < frames; ++i) app::drawn_image(scenes::field_page({panel}, width, height, 1.0), width, height);
    const double draw = seconds_since(t0);
    const auto dir = scratch_dir("frames");
    t0 = Clock::now();
    {
        media::VideoWriter video(dir / "frames.mp4", width, height);
        for (int i = 0; i < frames; ++i) video.add(app::drawn_image(scenes::field_page({panel}, width, height, 1.0), width, height));
        video.finish();
    }
    const double both = seconds_since(t0);
    std::filesystem::remove_all(dir);
    return {{"width", width},
            {"height", height},
            {"frames", frames},
            {"render_frames_per_second", frames / draw},
            {"render_and_encode_frames_per_second", frames / both}};
}

}  // namespace

nlohmann::json peer_comparison(const Paths& paths) {
    const std::filesystem::path python = "/usr/bin/python3", peer_file = paths.results / "peer.json";
    if (!std::filesystem::exists(python)) {
        std::fprintf(stderr, "figgen_accuracy: book's route skipped: no /usr/bin/python3 (apt-get install python3)\n");
        return {{"skipped", "no /usr/bin/python3"}};
    }
    std::fprintf(stderr, "figgen_accuracy: timing the book's numpy/scipy/matplotlib route (bench/book_peer.py)\n");
    timed(quoted(python) + " " + quoted(paths.source / "bench" / "book_peer.py") + " --out " + quoted(paths.results));
    nlohmann::json peer = nlohmann::json::parse(std::ifstream(peer_file));
    if (peer.contains("skipped")) return peer;
    nlohmann::json ours = nlohmann::json::array();
    for (const auto& row : peer.at("gray_scott")) ours.push_back(gray_scott_against(row));
    return {{"book", peer}, {"gray_scott", ours}, {"percolation", percolation_against(peer.at("percolation"))}};
}

nlohmann::json pipeline_times(const Paths& paths, const nlohmann::json& peer) {
    nlohmann::json out;
    const auto dir = scratch_dir("pipeline");
    const std::string figgen = quoted(paths.figgen);
    auto render = [&](const std::string& id, const std::string& options) {
        return timed(figgen + " render " + id + " --out " + quoted(dir) + " " + options + " >/dev/null");
    };

    // The nine printed tc7 figures in one process, PNG and metadata only (as
    // the book's route makes them), and, one process each, with their films.
    std::string nine;
    for (int i = 1; i <= 9; ++i) nine += " tc7-" + std::to_string(i);
    const double png_only = render(nine, "--no-video");
    nlohmann::json per_figure;
    double with_video = 0;
    for (int i = 1; i <= 9; ++i) {
        const std::string id = "tc7-" + std::to_string(i);
        const double video = render(id, "");
        per_figure[id] = {{"seconds_with_video", video}};
        with_video += video;
    }
    out["tc7_printed_figures"] = {{"seconds_png_one_process", png_only},
                                  {"seconds_with_video_one_process_each", with_video},
                                  {"per_figure", per_figure}};
    if (peer.contains("book") && peer["book"].contains("tc7_figures")) {
        const double book = peer["book"]["tc7_figures"].at("seconds").get<double>();
        out["tc7_printed_figures"]["book_matplotlib_seconds"] = book;
        out["tc7_printed_figures"]["speedup_over_book"] = book / png_only;
    }

    // tc7-2 with its 351-frame film against the same film made the book
    // reader's way (matplotlib's FFMpegWriter).
    if (peer.contains("book") && peer["book"].contains("tc7_2_film") &&
        peer["book"]["tc7_2_film"].contains("seconds")) {
        const double book = peer["book"]["tc7_2_film"].at("seconds").get<double>();
        const double ours = per_figure["tc7-2"].at("seconds_with_video").get<double>();
        out["tc7_2_film"] = {{"seconds", ours},
                             {"book_matplotlib_ffmpeg_seconds", book},
                             {"book_frames", peer["book"]["tc7_2_film"].at("frames")},
                             {"speedup_over_book", book / ours}};
    }

    // A real figure's film at 1280x720: tc7-2's 351 frames, with video minus without.
    const std::string hd = "--set 'animation.size=[1280,720]'";
    const double still = render("tc7-2", hd + " --no-video"), film = render("tc7-2", hd);
    const int frames = nlohmann::json::parse(std::ifstream(dir / "tc7-2.json"))["animation"].at("frames").get<int>();
    out["animation_1280x720"] = {{"figure", "tc7-2"},
                                 {"frames", frames},
                                 {"seconds_without_video", still},
                                 {"seconds_with_video", film},
                                 {"render_and_encode_frames_per_second", frames / (film - still)},
                                 {"in_process", frames_in_process()}};
    // The largest model of the catalog: 576 Gray-Scott runs.
    out["gs_atlas"] = {{"seconds", render("gs-atlas", "")}};
    // The Newman-Ziff threshold's 96 work items of samples on every core.
    out["pc_threshold"] = {{"seconds", render("pc-threshold", "")}};
    std::filesystem::remove_all(dir);

    // `make figures` from clean: no outputs, the program already built.
    std::filesystem::remove_all(paths.source / "out");
    // Outside any calling make's jobserver: the figures target runs -j nproc itself.
    const double all = timed("env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -C " + quoted(paths.source) +
                             " BUILD=" + quoted(paths.build) + " figures >/dev/null");
    int figures = 0;
    for (const auto& e : std::filesystem::directory_iterator(paths.source / "out"))
        figures += e.path().extension() == ".json";
    out["make_figures_from_clean"] = {{"seconds", all}, {"figures", figures}, {"jobs", 2}};
    if (peer.contains("book") && peer["book"].contains("tc7_figures"))
        out["make_figures_from_clean"]["times_book_nine_figures"] =
            all / peer["book"]["tc7_figures"].at("seconds").get<double>();
    return out;
}

nlohmann::json segment_lengths(const Paths& paths) {
    // Five catalog films (their own size, frames and fps) at each segment
    // length: the MP4's bytes against how many segments can be encoded at
    // once (one a core, at most one a segment), and the time of the whole
    // render on this machine.
    const std::vector<std::string> films = {"tc7-2", "bd-500", "tc7-ex2", "pl-phyllotaxis", "sf87-6"};
    const std::vector<int> lengths = {15, 30, 60, 120, 0};
    const auto dir = scratch_dir("segments");
    nlohmann::json rows = nlohmann::json::array();
    std::string table = "| film | frames | segment_frames | segments (most encoders at once) | MP4 bytes | against 120 | "
                        "seconds, this machine |\n|---|---|---|---|---|---|---|\n";
    for (const std::string& id : films) {
        double at_120 = 0;
        std::vector<nlohmann::json> film_rows;
        for (int length : lengths) {
            const auto out = dir / (id + "-" + std::to_string(length));
            const double seconds = timed(quoted(paths.figgen) + " render " + id + " --set animation.segment_frames=" +
                                         std::to_string(length) + " --out " + quoted(out) + " >/dev/null");
            const int frames =
                nlohmann::json::parse(std::ifstream(out / (id + ".json")))["animation"].at("frames").get<int>();
            const double bytes = double(std::filesystem::file_size(out / (id + ".mp4")));
            const int segments = length > 0 ? (frames + length - 1) / length : 1;
            if (length == 120) at_120 = bytes;
            film_rows.push_back({{"figure", id}, {"frames", frames}, {"segment_frames", length},
                                 {"segments", segments}, {"bytes", bytes}, {"seconds", seconds}});
            std::filesystem::remove_all(out);
        }
        for (nlohmann::json& row : film_rows) {
            const double ratio = at_120 > 0 ? row["bytes"].get<double>() / at_120 : 0;
            row["bytes_against_120"] = ratio;
            char line[256];
            std::snprintf(line, sizeof line, "| %s | %d | %d%s | %d | %.0f | %.2f | %.2f |\n", id.c_str(),
                          row["frames"].get<int>(), row["segment_frames"].get<int>(),
                          row["segment_frames"].get<int>() == 0 ? " (one)" : "", row["segments"].get<int>(),
                          row["bytes"].get<double>(), ratio, row["seconds"].get<double>());
            table += line;
            rows.push_back(row);
        }
    }
    std::filesystem::remove_all(dir);
    base::write_file_atomically(paths.results / "segments.md", table);
    std::printf("%s", table.c_str());
    return rows;
}

}  // namespace bench
