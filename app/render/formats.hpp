#pragma once
// The output formats, one entry each: what `--format` accepts and its help,
// the files' names, which files a figure gets, their disk and memory needs
// (from the measured constants beside their modules: media/video.hpp's
// film_costs, render/vector/vector.hpp's page and file bytes), how a vector
// format is drawn, and the gallery's links. Adding a format is one entry
// here and its writer.

#include <optional>
#include <string_view>
#include <vector>

#include "app/render/output_options.hpp"
#include "render/vector/vector.hpp"
#include "scenes/scene.hpp"

namespace app {

struct OutputFormat {
    // When its stage runs, for the memory estimate's order: with the figure
    // (after the PNG's canvas has gone) or with the film.
    enum class Stage { figure, film };

    const char* name = nullptr;    // the word --format (and a description's figure.formats) uses; null: not chosen by name
    const char* suffix = nullptr;  // the file's (or folder's) name after the figure's id
    const char* shown = nullptr;   // in messages: "the PNG"
    const char* help = nullptr;    // --format's help for it (null: not named there)
    const char* link = nullptr;    // the gallery's link to it (null: none, or linked otherwise)
    // Where the figure's JSON names its file ({"vector", "pdf"}: meta.vector.pdf.file).
    std::vector<const char*> json = {};
    std::optional<render::vector::Format> vector = std::nullopt;  // drawn on a vector page and written by the vector module
    Stage stage = Stage::figure;
    bool (*wanted)(const Description& d, const OutputOptions& options) = nullptr;
    void (*choose)(OutputOptions& options) = nullptr;  // --format names it (null: not chosen by name)
    // The most its file takes on disk.
    double (*disk)(const Description& d, const OutputOptions& options) = nullptr;
    // Its own stage's peak memory, beyond what every figure counts (the
    // canvas, the film's frames and its x264 encoders); null: nothing more.
    // Formats that share a stage (PDF and SVG) name it alike; it is counted once.
    scenes::MemoryNeed (*memory)(const Description& d, const OutputOptions& options) = nullptr;
};

// Every format, in the order of output_names.
const std::vector<OutputFormat>& output_formats();
// The format `--format` calls `name`, or null.
const OutputFormat* output_format(std::string_view name);
// The names --format accepts, in the table's order.
std::vector<std::string> format_names();
// What a refused --format says is allowed: "png, pdf, svg, ...".
std::string formats_allowed();
// --format's help, from the table.
std::string format_help();

}  // namespace app
