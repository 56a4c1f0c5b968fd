#pragma once
// The images that have goldens: a test pattern exercising every drawing
// primitive, and every figure description of the catalog rendered small.

#include <functional>
#include <string>
#include <vector>

#include "render/image.hpp"

namespace testkit {

struct GoldenCase {
    std::string name;                     // golden file stem
    std::function<render::Image()> make;  // renders it
};

// Shapes, both field samplings, two colormaps, text: 160 x 96 pixels.
render::Image test_pattern();

// Renders figure `id` of the catalog at `scale` without video, through the
// same code as `figgen render` (with `overrides` as its --set), and returns
// the PNG's decoded pixels.
render::Image render_catalog_figure(const std::string& id, double scale,
                                    const std::vector<std::string>& overrides = {});

// --set overrides a figure's golden is rendered with: a smaller run of the same
// scene for figures whose full run costs tens of seconds (gs-atlas), so the
// image test checks the drawing, not the machine's speed. Empty for the rest.
std::vector<std::string> golden_overrides(const std::string& id);

inline constexpr double golden_scale = 0.5;  // figures are checked at half size: small goldens

std::vector<GoldenCase> golden_cases();

}  // namespace testkit
