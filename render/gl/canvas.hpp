#pragma once
// A drawing surface of a given size: a 4x multisampled framebuffer (the most
// llvmpipe offers) that read() resolves into a single-sample one and reads
// back, or, made with one sample, a plain framebuffer read directly. Coordinates everywhere in render/ are pixels,
// origin at the top left, y down, as in the PNG that comes out. A canvas made with `depth` also has a multisampled
// depth buffer, for 3-D drawings (draw_tubes); 2-D drawing never tests depth.

#include <cstdint>
#include <deque>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "render/gl/gl.hpp"
#include "render/gl/gl_context.hpp"
#include "render/image.hpp"
#include "render/surface.hpp"

namespace render {

// A destroyed canvas of at most this many bytes of GL storage is kept for the
// next canvas of its size (see canvas.cpp); memory estimates count it.
inline constexpr double max_spare_canvas_bytes = 32.0 * 1024 * 1024;

// The GL backend of render/surface.hpp.
class Canvas : public Surface {
public:
    Canvas(int width, int height, int samples = canvas_samples, bool depth = false);
    ~Canvas() override;
    Canvas(const Canvas&) = delete;
    Canvas& operator=(const Canvas&) = delete;

    int width() const override { return width_; }
    int height() const override { return height_; }
    int samples() const { return samples_; }
    bool has_depth() const { return msaa_depth_ != 0; }
    // Pixel coordinates (top-left origin, y down) to clip space.
    const glm::mat4& projection() const { return projection_; }

    void bind() const;                    // makes this canvas the draw target
    void clear(const glm::vec4& colour);  // also binds; resets depth to far when there is a depth buffer
    // Resolves the samples and reads RGBA; on a transparent canvas, straight
    // (not premultiplied) colour, as PNG stores it.
    Image read() const;
    // The first half of read(), for FrameReader: resolves the samples and
    // starts reading them into the pixel buffer object bound to
    // GL_PIXEL_PACK_BUFFER (at its offset 0), bottom row first.
    void read_into_pack_buffer() const;


    // A transparent canvas's background() clears to alpha 0. Blending keeps
    // premultiplied colour in the framebuffer then (the alpha channel blends
    // with ONE, ONE_MINUS_SRC_ALPHA); read() divides it out.
    void set_transparent(bool transparent) { transparent_ = transparent; }
    bool transparent() const { return transparent_; }

    void background(const glm::vec4& colour) override;
    void shapes(const Shapes& shapes, Coverage coverage) override;
    void text(const Text& text) override;
    void field(const Rect& where, int rows, int cols, std::span<const double> values,
               const FieldStyle& style) override;
    void field_pair(const Rect& where, int rows, int cols, std::span<const double> first,
                    const FieldStyle& first_style, std::span<const double> second,
                    const FieldStyle& second_style) override;
    void hex_cells(const HexView& view, std::span<const glm::ivec2> cells, const glm::vec4& colour) override;
    void tubes(const Rect& viewport, const std::vector<Tube>& tubes, const std::vector<Facet>& facets,
               const Camera& camera, const Light& light, int sides) override;
    void clip(const Rect& box) override;
    void unclip() override;

private:
    // Resolves the samples (a multisampled canvas) and binds what holds the
    // pixels as GL_READ_FRAMEBUFFER, for read() and read_into_pack_buffer().
    void bind_for_reading() const;
    void make_resolve_target();

    bool transparent_ = false;

    int width_, height_, samples_;
    glm::mat4 projection_;
    GLuint msaa_fbo_ = 0, msaa_colour_ = 0;
    GLuint msaa_depth_ = 0;                        // 0 when made without depth
    GLuint resolve_fbo_ = 0, resolve_colour_ = 0;  // 0 with one sample: read straight from the canvas
    GLuint stencil_ = 0;  // for Coverage::once, made on first use; not kept with a spare canvas
};

// Frames read back through pixel buffer objects, up to `depth` in flight
// (frames_in_flight): glReadPixels into a buffer only queues the copy, so
// a GPU draws frame n + 1 while frame n travels to memory, and the copy is
// waited for (by mapping the buffer) only when the frame is taken,
// `depth` - 1 frames later. On llvmpipe the read happens at once; the pixels are the same.
// Frames come back in the order they were read, all the same size or not.
constexpr int frames_in_flight = 3;

class FrameReader {
public:
    explicit FrameReader(int depth = frames_in_flight);
    ~FrameReader();
    FrameReader(const FrameReader&) = delete;
    FrameReader& operator=(const FrameReader&) = delete;

    // Starts reading `canvas` as it is now (it may be drawn on again at
    // once); when `depth` frames are then in flight, waits for the oldest
    // and returns it.
    std::optional<Image> read(const Canvas& canvas);
    // The oldest frame in flight, waited for; nothing when none is.
    std::optional<Image> next();
    int in_flight() const { return static_cast<int>(flight_.size()); }

private:
    struct Slot {
        GLuint buffer = 0;
        std::size_t capacity = 0;  // bytes the buffer holds
        int width = 0, height = 0;
        bool transparent = false;
    };
    Image take(Slot& slot);

    int depth_;
    std::deque<Slot> flight_;
    std::vector<Slot> spare_;  // buffers read back, reused
};

}  // namespace render
