#pragma once
// figgen's subcommands: each adds its options to the command line and runs
// from what was parsed. main() only parses and dispatches.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/render/render_settings.hpp"

namespace app {

constexpr int exit_runtime_error = 1;  // a failure while running or writing
constexpr int exit_usage_error = 2;    // the command, a description or a value is wrong

// One line on stderr, "figgen: KIND: MESSAGE", whatever names and values
// the message quotes.
void say(const char* kind, const std::string& message);

// A subcommand: registered on the command line, run when given.
class Command {
public:
    virtual ~Command() = default;
    CLI::App* app = nullptr;  // its subcommand, set by add()
    // Runs it; throws UsageError for bad input. Returns the exit status.
    virtual int run() = 0;
};

struct ListCommand : Command {
    explicit ListCommand(CLI::App& parent);
    int run() override;
};

// figgen convert PATTERN.vti: Ready's pattern as a figgen description, on
// stdout or as OUT/ID.toml.
struct ConvertCommand : Command {
    explicit ConvertCommand(CLI::App& parent);
    int run() override;
    std::string pattern, out_dir;
};

struct DescribeCommand : Command {
    explicit DescribeCommand(CLI::App& parent);
    int run() override;
    std::string target;
};

// The gallery and the thumbnails decode images that anyone may have put in
// the folder: --max-memory (as render's, read by parse_size) bounds what an
// image's header may claim. 1 GiB holds every figure, poster and preview
// the catalog renders many times over, and refuses a PNG of 20000 x 20000.
constexpr const char* image_reading_max_memory = "1G";

struct GalleryCommand : Command {
    explicit GalleryCommand(CLI::App& parent);
    int run() override;
    std::string dir = "out";
    std::string max_memory = image_reading_max_memory;
};

struct ThumbnailsCommand : Command {
    explicit ThumbnailsCommand(CLI::App& parent);
    int run() override;
    std::string from = "out", to = "docs/thumbs";
    int width = 240, height = 180;
    std::string max_memory = image_reading_max_memory;
};

// figgen render, and figgen merge (the same options and --from): a merge
// computes nothing, it draws from the parts that shards wrote.
struct RenderCommand : Command, RenderSettings {
    explicit RenderCommand(CLI::App& parent, bool merge = false);
    int run() override;
    std::vector<std::string> targets;
};

}  // namespace app
