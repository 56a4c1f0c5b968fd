#pragma once
// The images that have goldens: three patterns exercising every drawing
// primitive, drawn in this process, and every figure description of the
// catalog rendered small through the figgen command.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/image.hpp"

namespace testkit {

struct Rendered {
    render::Image image;
    nlohmann::json meta;  // a figure's metadata (its JSON file); null for a pattern
    // With figgen_args asking for them (--format png,pdf,svg), the figure's
    // PDF and SVG, moved into a folder of their own that the caller removes.
    std::filesystem::path vector_dir;
};

struct GoldenCase {
    std::string name;  // golden file stem
    // Renders it; a figure through `figgen render` with `figgen_args`
    // added (e.g. "--gl egl --threads 2"), a pattern in this process.
    std::function<Rendered(const std::string& figgen_args)> make;
    bool figure = false;
};

// A figure's metadata with what rightly differs between machines and runs
// of the same bits removed: the GL it was drawn with (renderer), figgen's
// version, and the memory estimate (it counts the machine's cores); and the
// vector files it was asked for, which the goldens are not.
nlohmann::json comparable_metadata(nlohmann::json meta);

// Renders figure `id` through the figgen command (FIGGEN_EXE) at `scale`
// without video (--no-video, or figgen_args' --format), with `overrides` as
// --set and `figgen_args` added, into a private temporary folder;
// std::runtime_error with its output if it fails.
Rendered render_through_command(const std::string& id, double scale, const std::vector<std::string>& overrides,
                                const std::string& figgen_args);

// Shapes, both field samplings, two colormaps, text: 160 x 96 pixels.
render::Image test_pattern();

// Renders figure `id` of the catalog at `scale` without video, through the
// same code as `figgen render` (with `overrides` as its --set), and returns
// the PNG's decoded pixels.
render::Image render_catalog_figure(const std::string& id, double scale,
                                    const std::vector<std::string>& overrides = {});

// --set overrides a figure's golden is rendered with, one a line in
// tests/golden/<id>.set (# starts a comment): a smaller run of the same
// scene for figures whose full run costs tens of seconds (gs-atlas), so the
// image test checks the drawing, not the machine's speed. Empty for the rest.
std::vector<std::string> golden_overrides(const std::string& id);

inline constexpr double golden_scale = 0.5;  // figures are checked at half size: small goldens

std::vector<GoldenCase> golden_cases();

}  // namespace testkit
