#pragma once
// A figure's memory and disk estimates, checked against --max-memory and
// --max-disk before anything runs (app/render/estimates.cpp).

#include <string>
#include <vector>

#include "app/render/output_options.hpp"
#include "scenes/scene.hpp"

namespace app {

// The figure's size in pixels at the output scale.
int figure_width(const Description& d, const OutputOptions& options);
int figure_height(const Description& d, const OutputOptions& options);

// A figure's estimated peak memory: the model's `needs` (the scene's
// phase-1 estimate) plus the images it draws (figure, frames, encoder).
struct MemoryEstimate {
    double bytes = 0.0;
    scenes::MemoryNeed largest;
    // The film's segments encoded at once (app/render/segment_encoders.hpp): one
    // a core, at most one a segment, fewer where --max-memory would not
    // hold them; counted in `bytes`.
    int film_encoders = 1;
};
MemoryEstimate estimate_memory(const Description& d, const OutputOptions& options,
                               const std::vector<scenes::MemoryNeed>& needs);
// Refuses (UsageError) a figure whose estimate exceeds options.max_memory;
// the message gives the estimate and its largest part. Returns the estimate.
MemoryEstimate require_memory(const Description& d, const OutputOptions& options,
                              const std::vector<scenes::MemoryNeed>& needs);
// Refuses a figure whose outputs would take more than options.max_disk:
// each file's most (app/render/formats.hpp's table) and the parts of its work
// items kept while it runs (`parts_bytes`, the scene's bound).
void require_disk(const Description& d, const OutputOptions& options, double parts_bytes = 0);
// A film frame's pixels at the output scale (0 without a film).
double frame_pixels(const Description& d, const OutputOptions& options);
// Whether figure `d` gets a file drawn on a vector page (PDF, SVG).
bool writes_vector(const Description& d, const OutputOptions& options);
// "1.5 GiB", "12 MiB", "640 KiB", "100 bytes".
std::string format_bytes(double bytes);

}  // namespace app
