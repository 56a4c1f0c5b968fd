#pragma once
// Scenes: one per model family, the only code that knows both a model (sim/)
// and how to draw it (render/). A scene reads its [params] and [style],
// runs the model once to the last step any output needs, and writes the
// outputs through outputs.hpp.

#include <string>
#include <vector>

#include "figures/description.hpp"
#include "figures/outputs.hpp"
#include "figures/progress.hpp"

namespace figures {

using SceneFunction = void (*)(const Description&, const OutputOptions&, Progress&);

struct SceneInfo {
    std::string model;  // the description's `model`
    SceneFunction render;
    // The [style] keys naming its fields' colormaps: what --cmap sets
    // (empty: the scene draws no field). A key "X" comes with "X"'s sibling
    // list of colours, "colours" or "a_colours", which --cmap removes.
    std::vector<std::string> colormap_keys = {};
};

// Sets every colormap of a field figure to `name` (--cmap); throws
// UsageError for an unknown colormap or a figure without a field.
void apply_colormap(Description& d, const std::string& name);

const std::vector<SceneInfo>& scenes();

// Renders one figure; throws UsageError for bad descriptions or parameters,
// std::runtime_error for failures while writing.
void render_figure(const Description& d, const OutputOptions& options, Progress& progress);

// The scenes, each in its own file.
void render_diffusion(const Description& d, const OutputOptions& options, Progress& progress);
void render_gray_scott(const Description& d, const OutputOptions& options, Progress& progress);
void render_gray_scott_atlas(const Description& d, const OutputOptions& options, Progress& progress);
void render_percolation(const Description& d, const OutputOptions& options, Progress& progress);
void render_percolation_sizes(const Description& d, const OutputOptions& options, Progress& progress);
void render_cell1d(const Description& d, const OutputOptions& options, Progress& progress);
void render_cell_counts(const Description& d, const OutputOptions& options, Progress& progress);
void render_percolation_scaling(const Description& d, const OutputOptions& options, Progress& progress);
void render_percolation_phase(const Description& d, const OutputOptions& options, Progress& progress);
void render_forest_fire(const Description& d, const OutputOptions& options, Progress& progress);
void render_cell1d_survey(const Description& d, const OutputOptions& options, Progress& progress);
void render_snowflake(const Description& d, const OutputOptions& options, Progress& progress);
void render_snowflake_dimension(const Description& d, const OutputOptions& options, Progress& progress);
void render_hex_lattice(const Description& d, const OutputOptions& options, Progress& progress);
void render_phyllotaxis(const Description& d, const OutputOptions& options, Progress& progress);
void render_ifs(const Description& d, const OutputOptions& options, Progress& progress);
void render_deposition(const Description& d, const OutputOptions& options, Progress& progress);
void render_roughness(const Description& d, const OutputOptions& options, Progress& progress);
void render_lsystem(const Description& d, const OutputOptions& options, Progress& progress);
void render_lsystem_3d(const Description& d, const OutputOptions& options, Progress& progress);

}  // namespace figures
