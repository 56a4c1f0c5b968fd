// x264 settings from measurements: the same drawn frames of two films, a
// smooth field (tc7-2) and hard edges with text (bd-500), encoded through
// media::VideoWriter with several presets and tunes at crf 18, timed
// (encoding only: the frames are decoded from their PNGs first), weighed,
// and decoded by FFmpeg's ssim filter against the drawn frames. The default
// is the fastest setting that keeps every film's RGB SSIM within 0.005 of
// today's (medium, no tune) with files at most 25% larger (issue 17).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <regex>
#include <stdexcept>

#include "accuracy.hpp"
#include "base/atomic_file.hpp"
#include "media/png_io.hpp"
#include "media/video.hpp"

namespace bench {
namespace {

struct Film {
    std::string id;   // figure id
    std::string why;  // what its content asks of the encoder
};

struct Setting {
    std::string preset;
    std::string tune;  // "" = none
};

// Every preset from today's default down to the fastest, without a tune;
// the content tunes on the presets that could meet the bounds (ultrafast
// turns off the tools the tunes adjust, so its files are far larger).
std::vector<Setting> settings() {
    std::vector<Setting> out;
    for (const char* p : {"medium", "fast", "faster", "veryfast", "superfast", "ultrafast"}) out.push_back({p, ""});
    for (const char* p : {"medium", "fast", "faster", "veryfast", "superfast"})
        for (const char* t : {"animation", "stillimage"}) out.push_back({p, t});
    return out;
}

std::string quoted(const std::filesystem::path& p) {
    std::string s = "'";  // the project's paths hold no quote
    s += p.string();
    s += '\'';
    return s;
}

std::string name_of(const Setting& s) {
    return s.preset + (s.tune.empty() ? "" : "+" + s.tune);
}

// A command's standard output and error; throws when it fails.
std::string run_capturing(const std::string& command) {
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen((command + " 2>&1").c_str(), "r"), ::pclose);
    if (!pipe) throw std::runtime_error("cannot run: " + command);
    std::string out;
    std::array<char, 4096> buffer{};
    for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe.get())) > 0;)
        out.append(buffer.data(), n);
    const int status = ::pclose(pipe.release());
    if (status != 0)
        throw std::runtime_error("command failed (status " + std::to_string(status) + "): " + command + "\n" + out);
    return out;
}

// The film's frames as figgen draws them: `render --frames --no-video`
// writes ID-frames/00000.png, ... into `dir`.
std::vector<render::Image> drawn_frames(const Paths& paths, const std::string& id, const std::filesystem::path& dir) {
    run_capturing(quoted(paths.figgen) + " render " + id + " --frames --no-video --out " + quoted(dir));
    std::vector<render::Image> frames;
    char name[32];
    for (int i = 0;; ++i) {
        std::snprintf(name, sizeof name, "%05d.png", i);
        const auto file = dir / (id + "-frames") / name;
        if (!std::filesystem::exists(file)) break;
        frames.push_back(media::read_png(file).image);
    }
    if (frames.empty()) throw std::runtime_error("figgen wrote no frames for " + id + " into " + dir.string());
    return frames;
}

// The value after `label` in the summary line of the ssim filter whose
// line names `plane` ("R:" for the RGB comparison, "Y:" for the luma one).
double ssim_field(const std::string& log, const std::string& plane, const std::string& label) {
    const std::regex line("SSIM " + plane + "[^\\n]*");
    std::smatch m;
    if (!std::regex_search(log, m, line))
        throw std::runtime_error("no \"SSIM " + plane + "\" line in ffmpeg's output:\n" + log);
    const std::regex value(label + "([0-9.]+)");
    std::smatch v;
    const std::string text = m.str();
    if (!std::regex_search(text, v, value)) throw std::runtime_error("no " + label + " in: " + text);
    return std::stod(v.str(1));
}

struct Quality {
    double ssim_rgb;   // mean over frames of the RGB SSIM ("All" of R, G, B), decoded film against drawn PNGs
    double ssim_luma;  // the luma SSIM: drawn frames to BT.709 limited-range Y as the writer does, against the film's Y
};

// FFmpeg's ssim filter: the film decoded and turned back to RGB with the
// matrix it is tagged with, against the PNGs; and Y against Y, which leaves
// out yuv420p's halved chroma, the loss every setting shares.
Quality measure(const std::filesystem::path& film, const std::filesystem::path& frames) {
    const std::string inputs = "ffmpeg -nostdin -hide_banner -i " + quoted(film) + " -i " + quoted(frames / "%05d.png");
    const std::string rgb = run_capturing(inputs +
                                          " -lavfi \"[0:v]scale=in_color_matrix=bt709:in_range=tv,format=gbrp[a];"
                                          "[1:v]format=gbrp[b];[a][b]ssim\" -f null -");
    const std::string luma = run_capturing(inputs +
                                           " -lavfi \"[0:v]format=yuv420p[a];"
                                           "[1:v]scale=out_color_matrix=bt709:out_range=tv,format=yuv420p[b];"
                                           "[a][b]ssim\" -f null -");
    return {ssim_field(rgb, "R:", "All:"), ssim_field(luma, "Y:", "Y:")};
}

// Seconds to encode every frame through VideoWriter (add + finish), the best
// of `repeats` (the machine is shared: the least disturbed run).
double encode(const std::vector<render::Image>& frames, const std::filesystem::path& file, const Setting& s, int fps,
              int repeats) {
    media::VideoOptions options;
    options.codec = "libx264";
    options.fps = fps;
    options.threads = media::VideoOptions{}.threads;  // as figgen pins it
    options.crf = 18;
    options.preset = s.preset;
    options.tune = s.tune;
    double best = 1e300;
    for (int r = 0; r < repeats; ++r) {
        std::filesystem::remove(file);
        const auto t0 = Clock::now();
        media::VideoWriter writer(file, frames[0].width, frames[0].height, options);
        for (const auto& f : frames) writer.add(f);
        writer.finish();
        best = std::min(best, seconds_since(t0));
    }
    return best;
}

nlohmann::json film_rows(const Paths& paths, const Film& film, const std::filesystem::path& dir) {
    std::fprintf(stderr, "figgen_accuracy: encoder settings on %s's frames\n", film.id.c_str());
    const std::vector<render::Image> frames = drawn_frames(paths, film.id, dir);
    nlohmann::json rows = nlohmann::json::array();
    for (const Setting& s : settings()) {
        const auto file = dir / (film.id + "-" + name_of(s) + ".mp4");
        const double seconds = encode(frames, file, s, 30, 2);
        const Quality q = measure(file, dir / (film.id + "-frames"));
        const double n = static_cast<double>(frames.size());
        rows.push_back({{"preset", s.preset},
                        {"tune", s.tune},
                        {"seconds", seconds},
                        {"ms_per_frame", 1000 * seconds / n},
                        {"frames_per_second", n / seconds},
                        {"bytes", std::filesystem::file_size(file)},
                        {"ssim_rgb", q.ssim_rgb},
                        {"ssim_luma", q.ssim_luma}});
        std::filesystem::remove(file);
    }
    return {{"id", film.id},
            {"content", film.why},
            {"frames", frames.size()},
            {"size", {frames[0].width, frames[0].height}},
            {"rows", rows}};
}

// Each row against its film's reference row (medium, no tune): speed-up,
// size ratio, SSIM drop and whether it is inside both bounds.
void compare_to_reference(nlohmann::json& film, double ssim_drop, double size_growth) {
    const nlohmann::json reference = film["rows"][0];  // settings() lists medium, no tune, first
    for (auto& row : film["rows"]) {
        row["speedup"] = reference["seconds"].get<double>() / row["seconds"].get<double>();
        row["size_ratio"] = row["bytes"].get<double>() / reference["bytes"].get<double>();
        row["ssim_drop"] = reference["ssim_rgb"].get<double>() - row["ssim_rgb"].get<double>();
        row["within_bounds"] =
            row["ssim_drop"].get<double>() <= ssim_drop && row["size_ratio"].get<double>() <= 1 + size_growth;
    }
}

// The fastest setting (least encoding time over all films) inside the
// bounds on every film; the reference itself always is.
nlohmann::json choose(const nlohmann::json& out) {
    const auto& films = out["films"];
    std::size_t best = 0;
    double best_seconds = 1e300;
    for (std::size_t i = 0; i < films[0]["rows"].size(); ++i) {
        bool inside = true;
        double seconds = 0;
        for (const auto& f : films) {
            inside = inside && f["rows"][i]["within_bounds"].get<bool>();
            seconds += f["rows"][i]["seconds"].get<double>();
        }
        if (inside && seconds < best_seconds) best = i, best_seconds = seconds;
    }
    const auto& row = films[0]["rows"][best];
    return {{"preset", row["preset"]}, {"tune", row["tune"]}, {"seconds_all_films", best_seconds}};
}

std::string fixed(double x, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, x);
    return text;
}

// bench/results/encoder.md: one table per film, then the choice.
std::string markdown(const nlohmann::json& out) {
    std::string md =
        "# x264 settings on figgen's own frames (crf 18, " + std::to_string(media::VideoOptions{}.threads) + " encoder thread)\n\n"
        "Encoding time only (frames already in memory, best of 2); SSIM from FFmpeg's ssim filter, "
        "decoded film against the drawn PNGs: RGB (the bound) and luma. Bounds: SSIM drop <= 0.005, "
        "size <= 1.25 x medium's.\n";
    for (const auto& f : out["films"]) {
        md += "\n## " + f["id"].get<std::string>() + ": " + std::to_string(f["frames"].get<int>()) + " frames, " +
              std::to_string(f["size"][0].get<int>()) + " x " + std::to_string(f["size"][1].get<int>()) + " (" +
              f["content"].get<std::string>() +
              ")\n\n"
              "| preset | tune | encode s | ms/frame | frames/s | speed-up | KB | size ratio | SSIM RGB | drop | SSIM "
              "Y | inside |\n"
              "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
        for (const auto& r : f["rows"]) {
            const std::string tune = r["tune"].get<std::string>();
            md += "| " + r["preset"].get<std::string>() + " | " + (tune.empty() ? "none" : tune) + " | " +
                  fixed(r["seconds"], 2) + " | " + fixed(r["ms_per_frame"], 2) + " | " +
                  fixed(r["frames_per_second"], 0) + " | " + fixed(r["speedup"], 2) + " | " +
                  fixed(r["bytes"].get<double>() / 1000, 0) + " | " + fixed(r["size_ratio"], 3) + " | " +
                  fixed(r["ssim_rgb"], 4) + " | " + fixed(r["ssim_drop"], 4) + " | " + fixed(r["ssim_luma"], 4) +
                  " | " + (r["within_bounds"].get<bool>() ? "yes" : "no") + " |\n";
        }
    }
    const std::string tune = out["choice"]["tune"].get<std::string>();
    md += "\nChosen: preset " + out["choice"]["preset"].get<std::string>() + ", tune " +
          (tune.empty() ? "none" : tune) + " (the fastest inside the bounds on every film).\n";
    return md;
}

}  // namespace

nlohmann::json encoder_settings(const Paths& paths) {
    const auto dir = std::filesystem::temp_directory_path() / ("figgen-bench-encoder-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::vector<Film> films = {{"tc7-2", "smooth fields, slow change"},
                                     {"bd-500", "hard-edged cells, a growing deposit, a changing title"}};
    nlohmann::json out = {{"crf", 18},
                          {"threads", 2},
                          {"reference", {{"preset", "medium"}, {"tune", ""}}},
                          {"bounds", {{"ssim_drop", 0.005}, {"size_growth", 0.25}}},
                          {"films", nlohmann::json::array()}};
    for (const Film& f : films) {
        out["films"].push_back(film_rows(paths, f, dir));
        std::filesystem::remove_all(dir / (f.id + "-frames"));
    }
    std::filesystem::remove_all(dir);
    for (auto& f : out["films"]) compare_to_reference(f, 0.005, 0.25);
    out["choice"] = choose(out);
    base::write_file_atomically(paths.results / "encoder.json", out.dump(2) + "\n");
    base::write_file_atomically(paths.results / "encoder.md", markdown(out));
    return out;
}

}  // namespace bench
