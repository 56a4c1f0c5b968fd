#pragma once
// A drawing surface of a given size: a 4x multisampled framebuffer (the most
// llvmpipe offers) that read() resolves into a single-sample one and reads
// back, or, made with one sample, a plain framebuffer read directly. Coordinates everywhere in render/ are pixels,
// origin at the top left, y down, as in the PNG that comes out. A canvas made with `depth` also has a multisampled
// depth buffer, for 3-D drawings (draw_tubes); 2-D drawing never tests depth.

#include <glm/glm.hpp>

#include "render/gl.hpp"
#include "render/gl_context.hpp"
#include "render/image.hpp"

namespace render {

// The most triangles one GL draw call hands llvmpipe before glFinish. Its
// setup bins the triangles of a draw into scenes and queues up to 64 of them
// (tens of MiB each) while its threads rasterise, so one draw of millions of
// triangles peaked at hundreds of MiB more than its vertices, differently
// from run to run (pl-lsys-3d at depth 10: 324 to 484 MiB; 177 MiB without
// rasteriser threads). Drawn in batches of this many, finishing each, the
// queue holds one batch; the triangles and their order, so the pixels, are
// the same.
inline constexpr long long triangles_per_finish = 1 << 18;
// What that queue may hold on top of the triangles' own vertices, for memory
// estimates: measured 28 to 37 MiB above the vertices on the plant figures
// (pl-lsys-lycopodium at depth 6, pl-lsys-3d's film at depths 7 and 8).
inline constexpr double queued_triangles_bytes = 64.0 * 1024 * 1024;

// A destroyed canvas of at most this many bytes of GL storage is kept for the
// next canvas of its size (see canvas.cpp); memory estimates count it.
inline constexpr double max_spare_canvas_bytes = 32.0 * 1024 * 1024;

struct Rect {
    float x = 0, y = 0, w = 0, h = 0;  // top-left corner and size, pixels
    float right() const { return x + w; }
    float bottom() const { return y + h; }
    glm::vec2 centre() const { return {x + w / 2, y + h / 2}; }
};

class Canvas {
public:
    Canvas(int width, int height, int samples = canvas_samples, bool depth = false);
    ~Canvas();
    Canvas(const Canvas&) = delete;
    Canvas& operator=(const Canvas&) = delete;

    int width() const { return width_; }
    int height() const { return height_; }
    int samples() const { return samples_; }
    bool has_depth() const { return msaa_depth_ != 0; }
    // Pixel coordinates (top-left origin, y down) to clip space.
    const glm::mat4& projection() const { return projection_; }

    void bind() const;                    // makes this canvas the draw target
    void clear(const glm::vec4& colour);  // also binds; resets depth to far when there is a depth buffer
    Image read() const;                   // resolves the samples and reads RGBA

private:
    void make_resolve_target();

    int width_, height_, samples_;
    glm::mat4 projection_;
    GLuint msaa_fbo_ = 0, msaa_colour_ = 0;
    GLuint msaa_depth_ = 0;                        // 0 when made without depth
    GLuint resolve_fbo_ = 0, resolve_colour_ = 0;  // 0 with one sample: read straight from the canvas
};

}  // namespace render
