// A figure's estimates, made before anything runs: its memory (the scene's
// needs, the canvases, the film's frames and encoders, each format's own
// stage) and its disk (each file's most, from app/render/formats.hpp).

#include "app/render/estimates.hpp"

#include <algorithm>
#include <cstdio>

#include "app/render/formats.hpp"
#include "app/render/output_files.hpp"
#include "app/render/segment_encoders.hpp"
#include "media/video.hpp"
#include "render/gl/canvas.hpp"

namespace app {

using scenes::scaled;
using scenes::scaled_even;

int figure_width(const Description& d, const OutputOptions& options) {
    return scaled(d.width, options.scale);
}
int figure_height(const Description& d, const OutputOptions& options) {
    return scaled(d.height, options.scale);
}

std::string format_bytes(double bytes) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int unit = 0;
    while (bytes >= 1024.0 && unit < 6) {
        bytes /= 1024.0;
        ++unit;
    }
    char text[48];
    std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", bytes, units[unit]);
    return text;
}

namespace {

// What the process holds before any scene allocates: Mesa's llvmpipe with
// LLVM, FFmpeg, FreeType, HarfBuzz and fontconfig loaded and initialised.
// Measured as the peak RSS (wait4's ru_maxrss) of the smallest figure,
// tc7-6 --no-video --scale 0.1 (a 90 x 46 canvas): 108.6 MiB on Debian 12's
// Mesa 22.3 / LLVM 15; 120 MiB leaves room for another Mesa or font set.
// On top, the canvas an earlier figure in the same process may have left
// for reuse (render::max_spare_canvas_bytes).
constexpr double program_bytes = 120.0 * 1024 * 1024 + render::max_spare_canvas_bytes;
// A 2-D canvas: 4x multisampled colour (16 bytes a pixel), the resolved
// colour, the copy read back and the PNG rows or a frame's copy (12). llvmpipe
// touched 23 bytes a pixel of such a canvas at 2000^2 to 6000^2. A page of
// field panels on whole pixels has one sample (7 bytes a pixel measured at
// 6000^2), so counting 44 as before made its estimate 4.3 times its peak;
// a film's smooth pair adds its resampled values and their texture (16
// bytes a panel pixel, render/field.cpp), 23 in all, still inside 28, and a
// pass along the field's rows (8 bytes a field row per panel column): a
// 4000 x 4000 film of tc7-2 peaked at 754 MiB against an estimate of 2.0 GiB.
// 3-D scenes add their depth buffers themselves (lsystem_3d).
constexpr double canvas_bytes_per_pixel = 28.0;
// A film's segments encoded at once, memory aside: one a core (or a
// thread of --threads, where more), at most one a segment; one where the
// film is one segment or its frames go elsewhere (PNG sequence alone).
int film_encoders_wanted(const Description& d, const OutputOptions& options) {
    const int frames = d.animation->frame_count(), per_segment = d.animation->segment_frames;
    if (!options.encodes() || per_segment <= 0 || per_segment >= frames) return 1;
    const int segments = (frames + per_segment - 1) / per_segment;
    return std::max(1, std::min(segments, options.scene_options().threads));
}

}  // namespace

double frame_pixels(const Description& d, const OutputOptions& options) {
    if (!d.animation) return 0.0;
    return static_cast<double>(scaled_even(d.animation->width, options.scale)) *
           scaled_even(d.animation->height, options.scale);
}

bool writes_vector(const Description& d, const OutputOptions& options) {
    for (const OutputFormat& f : output_formats())
        if (f.vector && f.wanted(d, options)) return true;
    return false;
}

namespace {

// The memory of each wanted format of `stage` that has its own (a stage two
// formats share counted once).
void format_needs(const Description& d, const OutputOptions& options, OutputFormat::Stage stage,
                  std::vector<scenes::MemoryNeed>& all) {
    std::vector<std::string> counted;
    for (const OutputFormat& f : output_formats()) {
        if (f.stage != stage || !f.memory || !f.wanted(d, options)) continue;
        scenes::MemoryNeed need = f.memory(d, options);
        if (std::find(counted.begin(), counted.end(), need.what) != counted.end()) continue;
        counted.push_back(need.what);
        all.push_back(std::move(need));
    }
}

}  // namespace

MemoryEstimate estimate_memory(const Description& d, const OutputOptions& options,
                               const std::vector<scenes::MemoryNeed>& needs) {
    using scenes::MemoryNeed;
    namespace film = media::film_costs;
    std::vector<MemoryNeed> all = needs;
    int film_encoders = 1;
    all.push_back({"figure " + std::to_string(figure_width(d, options)) + " x " +
                       std::to_string(figure_height(d, options)) + " RGBA",
                   canvas_bytes_per_pixel * figure_width(d, options) * figure_height(d, options)});
    format_needs(d, options, OutputFormat::Stage::figure, all);
    if (d.animation && options.animates()) {
        const std::string size = std::to_string(scaled_even(d.animation->width, options.scale)) + " x " +
                                 std::to_string(scaled_even(d.animation->height, options.scale));
        all.push_back({"animation frames " + size, canvas_bytes_per_pixel * frame_pixels(d, options)});
        // The frames queued for the encoding thread and the one it is on,
        // and those read back through pixel buffers (render::FrameReader).
        all.push_back({"animation frames queued " + size,
                       4.0 * (FrameSink::frames_queued + 1 + render::frames_in_flight) * frame_pixels(d, options)});
        if (options.encodes()) {
            // Each segment's encoder, and, where several run at once, the
            // frames of each segment waiting for its encoder (all of a
            // segment's at worst). As many at once as fit --max-memory.
            const int frames = d.animation->frame_count(), per_segment = d.animation->segment_frames,
                      segment = per_segment > 0 && per_segment < frames ? per_segment : frames,
                      held = std::min(segment, film::x264_frames_held(options.video_options.preset));
            const double encoder =
                             film::x264_bytes + (film::x264_bytes_per_pixel + film::x264_bytes_per_pixel_frame * held) *
                                                    frame_pixels(d, options),
                         frame = 4.0 * frame_pixels(d, options);
            double others = program_bytes;
            for (const MemoryNeed& need : all) others += need.bytes;
            int encoders = film_encoders_wanted(d, options);
            // Side by side, each encoder and the frame it is on, and the
            // frames waiting (SegmentEncoders::waiting_most).
            const auto need = [&](int n) {
                return n * encoder + (n > 1 ? (n + SegmentEncoders::waiting_most(n, segment)) * frame : 0.0);
            };
            while (encoders > 1 && others + need(encoders) > static_cast<double>(options.max_memory)) --encoders;
            film_encoders = encoders;
            all.push_back({"the video encoder's frames " + size +
                               (encoders > 1 ? " (" + std::to_string(encoders) + " segments at once)" : ""),
                           need(encoders)});
        }
        format_needs(d, options, OutputFormat::Stage::film, all);
    }
    // The largest of what a setting can make smaller, then the program's own.
    MemoryEstimate estimate{program_bytes, all.front(), film_encoders};
    for (const MemoryNeed& need : all) {
        estimate.bytes += need.bytes;
        if (need.bytes > estimate.largest.bytes) estimate.largest = need;
    }
    return estimate;
}

MemoryEstimate require_memory(const Description& d, const OutputOptions& options,
                              const std::vector<scenes::MemoryNeed>& needs) {
    MemoryEstimate estimate = estimate_memory(d, options, needs);
    if (estimate.bytes > static_cast<double>(options.max_memory))
        throw UsageError(d.id + ": needs about " + format_bytes(estimate.bytes) + " of memory (" +
                         estimate.largest.what + ": " + format_bytes(estimate.largest.bytes) +
                         "), more than --max-memory " + format_bytes(static_cast<double>(options.max_memory)) +
                         "; make it smaller or raise --max-memory");
    return estimate;
}

void require_disk(const Description& d, const OutputOptions& options, double parts_bytes) {
    double bytes = parts_bytes, most = parts_bytes;
    std::string largest = "the parts of its work items";
    for (const OutputFormat& f : output_formats()) {
        if (!f.wanted(d, options)) continue;
        const double need = f.disk(d, options);
        bytes += need;
        if (need > most) most = need, largest = f.shown;
    }
    if (bytes > static_cast<double>(options.max_disk))
        throw UsageError(d.id + ": its outputs would take up to about " + format_bytes(bytes) + " (mostly " + largest +
                         "), more than --max-disk " + format_bytes(static_cast<double>(options.max_disk)) +
                         "; make it smaller, leave out the video or raise --max-disk");
}

}  // namespace app
