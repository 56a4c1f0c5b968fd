#include "app/render/formats.hpp"

#include <algorithm>
#include <string>

#include "app/render/estimates.hpp"
#include "media/video.hpp"

namespace app {

namespace {

using scenes::scaled_even;

double figure_pixels(const Description& d, const OutputOptions& options) {
    return static_cast<double>(figure_width(d, options)) * figure_height(d, options);
}
// Every frame's pixels: the film's size times its frames.
double film_pixels(const Description& d, const OutputOptions& options) {
    return d.animation ? d.animation->frame_count() * frame_pixels(d, options) : 0.0;
}
bool films(const Description& d) {
    return d.animation.has_value();
}
bool asks(const Description& d, const char* format) {
    return std::find(d.formats.begin(), d.formats.end(), format) != d.formats.end();
}
// A vector format: --format's choice, or else the description's figure.formats.
bool chosen(const Description& d, const OutputOptions& o, const char* format) {
    return o.formats_given ? o.chosen.count(format) > 0 : asks(d, format);
}
std::string film_size(const Description& d, const OutputOptions& options) {
    return std::to_string(scaled_even(d.animation->width, options.scale)) + " x " +
           std::to_string(scaled_even(d.animation->height, options.scale));
}

scenes::MemoryNeed vector_page(const Description& d, const OutputOptions& options) {
    return {"the PDF and SVG's vector page",
            render::vector::page_bytes + render::vector::page_bytes_per_pixel * figure_pixels(d, options)};
}

std::vector<OutputFormat> make_table() {
    using render::vector::Format;
    using Stage = OutputFormat::Stage;
    namespace film = media::film_costs;
    std::vector<OutputFormat> t;
    const auto always = [](const Description&, const OutputOptions&) { return true; };
    t.push_back({.name = "png",
                 .suffix = ".png",
                 .shown = "the PNG",
                 .help = "png (nothing more)",
                 .wanted = always,
                 .choose = [](OutputOptions&) {},
                 .disk = [](const Description& d, const OutputOptions& o) { return 4.0 * figure_pixels(d, o); }});
    t.push_back({.suffix = ".json",
                 .shown = "the JSON",
                 .wanted = always,
                 .disk = [](const Description&, const OutputOptions&) { return 0.0; }});
    // Vector files: --format's, or else those the description asks for.
    const auto vector_bytes = [](const Description& d, const OutputOptions& o) {
        return render::vector::file_bytes(figure_width(d, o), figure_height(d, o));
    };
    t.push_back({.name = "pdf",
                 .suffix = ".pdf",
                 .shown = "the PDF",
                 .help = "pdf and svg (the figure as vector graphics)",
                 .link = "PDF",
                 .json = {"vector", "pdf"},
                 .vector = Format::pdf,
                 .wanted = [](const Description& d, const OutputOptions& o) { return chosen(d, o, "pdf"); },
                 .choose = [](OutputOptions& o) { o.chosen.insert("pdf"); },
                 .disk = vector_bytes,
                 .memory = vector_page});
    t.push_back({.name = "svg",
                 .suffix = ".svg",
                 .shown = "the SVG",
                 .link = "SVG",
                 .json = {"vector", "svg"},
                 .vector = Format::svg,
                 .wanted = [](const Description& d, const OutputOptions& o) { return chosen(d, o, "svg"); },
                 .choose = [](OutputOptions& o) { o.chosen.insert("svg"); },
                 .disk = vector_bytes,
                 .memory = vector_page});
    // A film's file, MP4 or WebM: at most the measured bytes a pixel and frame.
    const auto film_file_bytes = [](const Description& d, const OutputOptions& o) {
        return film::file_bytes_per_pixel_frame * film_pixels(d, o);
    };
    // The MP4 is encoded for the WebM too, kept or not.
    t.push_back({.name = "mp4",
                 .suffix = ".mp4",
                 .shown = "the MP4",
                 .help = "mp4 (the animation)",
                 .stage = Stage::film,
                 .wanted = [](const Description& d, const OutputOptions& o) { return films(d) && o.encodes(); },
                 .choose = [](OutputOptions& o) { o.video = true; },
                 .disk = film_file_bytes});
    // The film's looping preview, with its MP4: at most its budget.
    t.push_back({.suffix = ".webp",
                 .shown = "the preview",
                 .stage = Stage::film,
                 .wanted = [](const Description& d, const OutputOptions& o) { return films(d) && o.encodes(); },
                 .disk = [](const Description&, const OutputOptions&) {
                     return static_cast<double>(media::PreviewOptions{}.max_bytes);
                 },
                 // Its frames, at most max_frames fitted into its size, held
                 // from their segments' encoding to the film's end.
                 .memory = [](const Description& d, const OutputOptions& o) -> scenes::MemoryNeed {
                     const media::PreviewOptions preview;
                     const double fit = std::min(
                         {1.0, double(preview.max_width) / std::max(1, scaled_even(d.animation->width, o.scale)),
                          double(preview.max_height) / std::max(1, scaled_even(d.animation->height, o.scale))});
                     return {"the preview's frames", 4.0 * std::min(preview.max_frames, d.animation->frame_count()) *
                                                         fit * fit * frame_pixels(d, o)};
                 }});
    t.push_back({.name = "webm",
                 .suffix = ".webm",
                 .shown = "the WebM",
                 .help = "webm (the animation as VP9 in WebM)",
                 .link = "WebM",
                 .json = {"animation", "webm"},
                 .stage = Stage::film,
                 .wanted = [](const Description& d, const OutputOptions& o) { return films(d) && o.webm; },
                 .choose = [](OutputOptions& o) { o.webm = true; },
                 .disk = film_file_bytes,
                 .memory = [](const Description& d, const OutputOptions& o) -> scenes::MemoryNeed {
                     return {"the WebM encoder " + film_size(d, o),
                             film::vp9_bytes + film::vp9_bytes_per_pixel * frame_pixels(d, o)};
                 }});
    t.push_back({.name = "frames",
                 .suffix = "-frames",
                 .shown = "the PNG sequence",
                 .help = "frames (the animation as a PNG sequence)",
                 .stage = Stage::film,
                 .wanted = [](const Description& d, const OutputOptions& o) { return films(d) && o.frames; },
                 .choose = [](OutputOptions& o) { o.frames = true; },
                 .disk = [](const Description& d, const OutputOptions& o) { return 4.0 * film_pixels(d, o); }});
    // A file the figure's scene writes besides it (SceneInfo::extra_files).
    t.push_back({.name = "vti",
                 .suffix = ".vti",
                 .shown = "the VTI file",
                 .help = "vti (a formula model's last step as Ready's file)",
                 .link = "VTI",
                 .json = {"vti"},
                 .wanted = [](const Description&, const OutputOptions& o) { return o.vti; },
                 .choose = [](OutputOptions& o) { o.vti = true; },
                 .disk = [](const Description& d, const OutputOptions&) {
                     const scenes::ExtraFile* file = scenes::extra_file(d, "vti");
                     return file ? file->disk(d) : 0.0;
                 }});
    t.push_back({.name = "vtu",
                 .suffix = ".vtu",
                 .shown = "the VTU file",
                 .help = "vtu (a mesh model's last step as Ready's file)",
                 .link = "VTU",
                 .json = {"vtu"},
                 .wanted = [](const Description&, const OutputOptions& o) { return o.vtu; },
                 .choose = [](OutputOptions& o) { o.vtu = true; },
                 .disk = [](const Description& d, const OutputOptions&) {
                     const scenes::ExtraFile* file = scenes::extra_file(d, "vtu");
                     return file ? file->disk(d) : 0.0;
                 }});
    return t;
}

}  // namespace

const std::vector<OutputFormat>& output_formats() {
    static const std::vector<OutputFormat> table = make_table();
    return table;
}

const OutputFormat* output_format(std::string_view name) {
    for (const OutputFormat& f : output_formats())
        if (f.name && name == f.name) return &f;
    return nullptr;
}

std::vector<std::string> format_names() {
    std::vector<std::string> names;
    for (const OutputFormat& f : output_formats())
        if (f.name && f.choose) names.emplace_back(f.name);
    return names;
}

std::string formats_allowed() {
    std::string names;
    for (const std::string& n : format_names()) names += (names.empty() ? "" : ", ") + n;
    return names;
}

std::string format_help() {
    std::string items;
    for (const OutputFormat& f : output_formats())
        if (f.help) items += std::string(items.empty() ? "" : ", ") + f.help;
    return "What to write besides the PNG and its JSON, a list (e.g. png,pdf,mp4): " + items +
           "; default: mp4, and the pdf or svg the description's figure.formats asks for";
}

}  // namespace app
