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
    namespace film = render::film_costs;
    std::vector<OutputFormat> t;
    t.push_back({"png", ".png", "the PNG", "png (nothing more)", nullptr, {}, std::nullopt, Stage::figure,
                 [](const Description&, const OutputOptions&) { return true; }, [](OutputOptions&) {},
                 [](const Description& d, const OutputOptions& o) { return 4.0 * figure_pixels(d, o); }});
    t.push_back({nullptr, ".json", "the JSON", nullptr, nullptr, {}, std::nullopt, Stage::figure,
                 [](const Description&, const OutputOptions&) { return true; }, nullptr,
                 [](const Description&, const OutputOptions&) { return 0.0; }});
    // Vector files: --format's, or else those the description asks for.
    t.push_back({"pdf", ".pdf", "the PDF", "pdf and svg (the figure as vector graphics)", "PDF", {"vector", "pdf"},
                 Format::pdf, Stage::figure,
                 [](const Description& d, const OutputOptions& o) { return chosen(d, o, "pdf"); },
                 [](OutputOptions& o) { o.chosen.insert("pdf"); },
                 [](const Description& d, const OutputOptions& o) {
                     return render::vector::file_bytes(figure_width(d, o), figure_height(d, o));
                 },
                 vector_page});
    t.push_back({"svg", ".svg", "the SVG", nullptr, "SVG", {"vector", "svg"}, Format::svg, Stage::figure,
                 [](const Description& d, const OutputOptions& o) { return chosen(d, o, "svg"); },
                 [](OutputOptions& o) { o.chosen.insert("svg"); },
                 [](const Description& d, const OutputOptions& o) {
                     return render::vector::file_bytes(figure_width(d, o), figure_height(d, o));
                 },
                 vector_page});
    // The MP4 is encoded for the WebM too, kept or not.
    t.push_back({"mp4", ".mp4", "the MP4", "mp4 (the animation)", nullptr, {}, std::nullopt, Stage::film,
                 [](const Description& d, const OutputOptions& o) { return films(d) && o.encodes(); },
                 [](OutputOptions& o) { o.video = true; },
                 [](const Description& d, const OutputOptions& o) {
                     return film::file_bytes_per_pixel_frame * film_pixels(d, o);
                 }});
    // The film's looping preview, with its MP4: at most its budget.
    t.push_back({nullptr,
                 ".webp",
                 "the preview",
                 nullptr,
                 nullptr,
                 {},
                 std::nullopt,
                 Stage::film,
                 [](const Description& d, const OutputOptions& o) { return films(d) && o.encodes(); },
                 nullptr,
                 [](const Description&, const OutputOptions&) {
                     return static_cast<double>(render::PreviewOptions{}.max_bytes);
                 },
                 // Its frames, at most max_frames fitted into its size, held
                 // from their segments' encoding to the film's end.
                 [](const Description& d, const OutputOptions& o) -> scenes::MemoryNeed {
                     const render::PreviewOptions preview;
                     const double fit = std::min(
                         {1.0, double(preview.max_width) / std::max(1, scaled_even(d.animation->width, o.scale)),
                          double(preview.max_height) / std::max(1, scaled_even(d.animation->height, o.scale))});
                     return {"the preview's frames", 4.0 * std::min(preview.max_frames, d.animation->frame_count()) *
                                                         fit * fit * frame_pixels(d, o)};
                 }});
    t.push_back({"webm",
                 ".webm",
                 "the WebM",
                 "webm (the animation as VP9 in WebM)",
                 "WebM",
                 {"animation", "webm"},
                 std::nullopt,
                 Stage::film,
                 [](const Description& d, const OutputOptions& o) { return films(d) && o.webm; },
                 [](OutputOptions& o) { o.webm = true; },
                 [](const Description& d, const OutputOptions& o) {
                     return film::file_bytes_per_pixel_frame * film_pixels(d, o);
                 },
                 [](const Description& d, const OutputOptions& o) -> scenes::MemoryNeed {
                     return {"the WebM encoder " + film_size(d, o),
                             film::vp9_bytes + film::vp9_bytes_per_pixel * frame_pixels(d, o)};
                 }});
    t.push_back({"frames", "-frames", "the PNG sequence", "frames (the animation as a PNG sequence)", nullptr, {},
                 std::nullopt, Stage::film,
                 [](const Description& d, const OutputOptions& o) { return films(d) && o.frames; },
                 [](OutputOptions& o) { o.frames = true; },
                 [](const Description& d, const OutputOptions& o) { return 4.0 * film_pixels(d, o); }});
    t.push_back({"vti", ".vti", "the VTI file", "vti (a formula model's last step as Ready's file)", "VTI", {"vti"},
                 std::nullopt, Stage::figure, [](const Description&, const OutputOptions& o) { return o.vti; },
                 [](OutputOptions& o) { o.vti = true; },
                 [](const Description& d, const OutputOptions&) {
                     const scenes::ExtraFile* file = scenes::extra_file(d, "vti");
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
