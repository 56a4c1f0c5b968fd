#pragma once
// Rendering one figure, in the scene's three phases: read and check every
// setting (and the memory and disk estimates) before anything runs, then run
// the model and draw, with all of the figure's new files put in place
// together.

#include <memory>

#include "app/render/output_files.hpp"
#include "description/description.hpp"
#include "scenes/output.hpp"
#include "scenes/scene.hpp"

namespace app {

// Phase 1: `d`'s scene with every setting read and checked, and the figure's
// memory and disk estimates within options' limits. Throws UsageError that
// says where a bad setting was given; nothing has run and nothing is created.
std::unique_ptr<scenes::Scene> check_figure(const Description& d, const OutputOptions& options);

// The output folder (options.dir), created if missing and open; UsageError
// when it cannot be made or written. Call after every figure's phase 1: a
// refused run creates nothing.
base::Folder open_output_folder(const OutputOptions& options);

// Phases 2 and 3 of a checked figure: takes the figure's turn against other
// figgen processes (removing what a killed one left), runs the scene and
// puts its files in place in `folder`, all together or none.
void render_figure(const Description& d, const scenes::Scene& scene, const base::Folder& folder,
                   const OutputOptions& options, scenes::Progress& progress);

// All three phases.
void render_figure(const Description& d, const OutputOptions& options, scenes::Progress& progress);

}  // namespace app
