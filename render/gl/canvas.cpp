#include "render/gl/canvas.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <string>

#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_context.hpp"
#include "render/shapes.hpp"

namespace render {
namespace {
// One canvas's GL objects kept when it is destroyed, for the next canvas of
// the same size and kind: a new renderbuffer costs llvmpipe an allocation
// that it zero-fills (page faults and a memset of 20 bytes a pixel). The nine
// printed tc7 figures in one process, eight of them 900 x 450, took 0.79 s
// instead of 0.97 s (median of 9 runs each).
struct Spare {
    int width = 0, height = 0, samples = 0;
    bool depth = false;
    GLuint msaa_fbo = 0, msaa_colour = 0, msaa_depth = 0, resolve_fbo = 0, resolve_colour = 0;
};
Spare spare;

void delete_objects(const Spare& s) {
    if (s.resolve_fbo) glDeleteFramebuffers(1, &s.resolve_fbo);
    if (s.resolve_colour) glDeleteRenderbuffers(1, &s.resolve_colour);
    if (s.msaa_fbo) glDeleteFramebuffers(1, &s.msaa_fbo);
    if (s.msaa_colour) glDeleteRenderbuffers(1, &s.msaa_colour);
    if (s.msaa_depth) glDeleteRenderbuffers(1, &s.msaa_depth);
}
// The GL storage a canvas holds: its samples, their depth, the resolved copy.
double spare_canvas_bytes(int width, int height, int samples, bool depth) {
    return static_cast<double>(width) * height *
           (4.0 * samples + (depth ? 4.0 * samples : 0.0) + (samples > 1 ? 4.0 : 0.0));
}
}  // namespace

Canvas::Canvas(int width, int height, int samples, bool depth)
    : width_(width), height_(height), samples_(samples) {
    // Exactly canvas_samples, never the most the GL has: the pixels must
    // not change with the machine.
    if (samples != 1 && samples != canvas_samples)
        throw std::invalid_argument("canvas samples " + std::to_string(samples) + ": allowed 1 or " +
                                    std::to_string(canvas_samples));
    GlContext::get();
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    if (width < 1 || height < 1 || width > max_size || height > max_size)
        throw std::invalid_argument("canvas size " + std::to_string(width) + "x" + std::to_string(height) +
                                    " is out of range: allowed 1.." + std::to_string(max_size) + " pixels a side");
    // y down: the top edge of the canvas is y = 0.
    projection_ = glm::ortho(0.0f, float(width), float(height), 0.0f, -1.0f, 1.0f);

    if (spare.msaa_fbo && spare.width == width && spare.height == height && spare.samples == samples_ &&
        spare.depth == depth) {
        msaa_fbo_ = spare.msaa_fbo, msaa_colour_ = spare.msaa_colour, msaa_depth_ = spare.msaa_depth;
        resolve_fbo_ = spare.resolve_fbo, resolve_colour_ = spare.resolve_colour;
        spare = Spare{};
        clear(glm::vec4(0.0f));  // as new renderbuffers come from llvmpipe
        check_gl("Canvas");
        return;
    }
    delete_objects(spare);  // before allocating: a kept canvas never adds to the peak
    spare = Spare{};

    // One sample is a plain renderbuffer: asked for 1 sample, Mesa rounds up
    // to the smallest multisampled count it has (4 on llvmpipe).
    auto storage = [&](GLenum format) {
        if (samples_ > 1)
            glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, format, width, height);
        else
            glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
        // The GL may give more samples than asked for (the spec allows it).
        GLint given = 0;
        glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &given);
        if (std::max(given, 1) != samples_)
            throw std::runtime_error("the GL gave a canvas " + std::to_string(given) + " samples a pixel for the " +
                                     std::to_string(samples_) + " asked for");
    };
    glGenRenderbuffers(1, &msaa_colour_);
    glBindRenderbuffer(GL_RENDERBUFFER, msaa_colour_);
    storage(GL_RGBA8);
    glGenFramebuffers(1, &msaa_fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_colour_);
    if (depth) {
        // Same sample count as the colour: a multisampled FBO needs its attachments to agree.
        glGenRenderbuffers(1, &msaa_depth_);
        glBindRenderbuffer(GL_RENDERBUFFER, msaa_depth_);
        storage(GL_DEPTH_COMPONENT24);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth_);
    }
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("multisampled framebuffer incomplete");

    if (samples_ > 1) make_resolve_target();
    bind();
    check_gl("Canvas");
}

// The single-sample framebuffer read() resolves the samples into.
void Canvas::make_resolve_target() {
    glGenRenderbuffers(1, &resolve_colour_);
    glBindRenderbuffer(GL_RENDERBUFFER, resolve_colour_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width_, height_);
    glGenFramebuffers(1, &resolve_fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_colour_);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("resolve framebuffer incomplete");
}

Canvas::~Canvas() {
    if (stencil_) glDeleteRenderbuffers(1, &stencil_);
    if (spare_canvas_bytes(width_, height_, samples_, msaa_depth_ != 0) <= max_spare_canvas_bytes) {
        delete_objects(spare);
        spare = Spare{width_,       height_,     samples_,     msaa_depth_ != 0, msaa_fbo_,
                      msaa_colour_, msaa_depth_, resolve_fbo_, resolve_colour_};
        return;
    }
    if (resolve_fbo_) glDeleteFramebuffers(1, &resolve_fbo_);
    if (resolve_colour_) glDeleteRenderbuffers(1, &resolve_colour_);
    glDeleteFramebuffers(1, &msaa_fbo_);
    glDeleteRenderbuffers(1, &msaa_colour_);
    if (msaa_depth_) glDeleteRenderbuffers(1, &msaa_depth_);
}

void Canvas::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_);
    glViewport(0, 0, width_, height_);
    // Straight alpha for colour, and coverage accumulates in alpha so the
    // resolved image over a white background stays opaque.
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glEnable(GL_MULTISAMPLE);
}

void Canvas::clear(const glm::vec4& colour) {
    bind();
    glClearColor(colour.r, colour.g, colour.b, colour.a);
    if (msaa_depth_) {
        glDepthMask(GL_TRUE);  // glClear honours the depth write mask
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    } else {
        glClear(GL_COLOR_BUFFER_BIT);
    }
}

void Canvas::bind_for_reading() const {
    if (resolve_fbo_) {  // multisampled: resolve first
        glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo_);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
        glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_ ? resolve_fbo_ : msaa_fbo_);
}

void Canvas::read_into_pack_buffer() const {
    bind_for_reading();
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    check_gl("Canvas::read_into_pack_buffer");
    bind();
}

namespace {

// `bottom_up` (width x height RGBA in GL's row order) as an image, rows
// top-down; straight alpha when the canvas was transparent (premultiplied
// in the framebuffer, see set_transparent).
Image image_of_rows(const std::uint8_t* bottom_up, int width, int height, bool transparent) {
    Image image(width, height);
    const std::size_t stride = static_cast<std::size_t>(width) * 4;
    for (int y = 0; y < height; ++y)
        std::copy_n(bottom_up + static_cast<std::size_t>(height - 1 - y) * stride, stride,
                    image.rgba.data() + static_cast<std::size_t>(y) * stride);
    if (transparent) {
        for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
            const unsigned a = image.rgba[i + 3];
            if (a == 0 || a == 255) continue;
            for (std::size_t c = 0; c < 3; ++c)
                image.rgba[i + c] = static_cast<std::uint8_t>(std::min(255u, (image.rgba[i + c] * 255u + a / 2) / a));
        }
    }
    return image;
}

}  // namespace

Image Canvas::read() const {
    bind_for_reading();
    glFinish();  // llvmpipe renders lazily: wait before reading
    std::vector<std::uint8_t> rows(static_cast<std::size_t>(width_) * height_ * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    check_gl("Canvas::read");
    bind();
    return image_of_rows(rows.data(), width_, height_, transparent_);
}

FrameReader::FrameReader(int depth) : depth_(depth < 1 ? 1 : depth) {}

FrameReader::~FrameReader() {
    for (Slot& s : flight_) glDeleteBuffers(1, &s.buffer);
    for (Slot& s : spare_) glDeleteBuffers(1, &s.buffer);
}

std::optional<Image> FrameReader::read(const Canvas& canvas) {
    Slot slot;
    if (!spare_.empty()) {
        slot = spare_.back();
        spare_.pop_back();
    } else {
        glGenBuffers(1, &slot.buffer);
    }
    const std::size_t bytes = static_cast<std::size_t>(canvas.width()) * canvas.height() * 4;
    glBindBuffer(GL_PIXEL_PACK_BUFFER, slot.buffer);
    if (slot.capacity != bytes) {
        glBufferData(GL_PIXEL_PACK_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, GL_STREAM_READ);
        slot.capacity = bytes;
    }
    canvas.read_into_pack_buffer();
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glFlush();  // the copy starts now, not when the frame is taken
    slot.width = canvas.width();
    slot.height = canvas.height();
    slot.transparent = canvas.transparent();
    flight_.push_back(slot);
    check_gl("FrameReader::read");
    if (static_cast<int>(flight_.size()) < depth_) return std::nullopt;
    return next();
}

std::optional<Image> FrameReader::next() {
    if (flight_.empty()) return std::nullopt;
    Slot slot = flight_.front();
    flight_.pop_front();
    Image image = take(slot);
    spare_.push_back(slot);
    return image;
}

Image FrameReader::take(Slot& slot) {
    // Mapping waits for the copy into the buffer (GL orders it after the
    // read), which by now has had depth - 1 frames' time. No fence: a fence
    // deleted just after its wait returned hung llvmpipe once in a test run
    // (its rasterizer thread still signalling the fence's condition
    // variable, freed and, under glibc's M_PERTURB while x264 runs, filled).
    glBindBuffer(GL_PIXEL_PACK_BUFFER, slot.buffer);
    const void* mapped = glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, static_cast<GLsizeiptr>(slot.capacity),
                                          GL_MAP_READ_BIT);
    if (!mapped) {
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        check_gl("FrameReader: mapping a frame");
        throw std::runtime_error("FrameReader: GL could not map a frame's buffer");
    }
    // As the canvas was when read (its size and transparency then).
    Image image = image_of_rows(static_cast<const std::uint8_t*>(mapped), slot.width, slot.height, slot.transparent);
    glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    check_gl("FrameReader: reading a frame");
    return image;
}

void Canvas::background(const glm::vec4& colour) { clear(transparent_ ? glm::vec4(0.0f) : colour); }

void Canvas::shapes(const Shapes& shapes, Coverage coverage) {
    if (coverage == Coverage::each) return gl_backend::shapes(*this, shapes);
    // Once: a stencil buffer, lent to the multisampled framebuffer for the
    // draw, passes each sample's first fragment only. Without one (an
    // incomplete framebuffer) the shapes are drawn plainly.
    bind();
    if (!stencil_) {
        glGenRenderbuffers(1, &stencil_);
        glBindRenderbuffer(GL_RENDERBUFFER, stencil_);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_STENCIL_INDEX8, width_, height_);
    }
    glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER, stencil_);
    const bool attached = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    if (attached) {
        glClearStencil(0);
        glClear(GL_STENCIL_BUFFER_BIT);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_EQUAL, 0, 0xFF);
        glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    } else {
        glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER, 0);
    }
    gl_backend::shapes(*this, shapes);
    glDisable(GL_STENCIL_TEST);
    if (attached) glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER, 0);
    check_gl("Canvas::shapes");
}

void Canvas::text(const Text& text) { gl_backend::text(*this, text); }

void Canvas::field(const Rect& where, int rows, int cols, std::span<const double> values, const FieldStyle& style) {
    const std::span<const double> layers[] = {values};
    const FieldStyle* styles[] = {&style};
    gl_backend::field(*this, where, rows, cols, layers, styles);
}

void Canvas::field_pair(const Rect& where, int rows, int cols, std::span<const double> first,
                        const FieldStyle& first_style, std::span<const double> second,
                        const FieldStyle& second_style) {
    const std::span<const double> layers[] = {first, second};
    const FieldStyle* styles[] = {&first_style, &second_style};
    gl_backend::field(*this, where, rows, cols, layers, styles);
}

void Canvas::hex_cells(const HexView& view, std::span<const glm::ivec2> cells, const glm::vec4& colour) {
    gl_backend::hex_cells(*this, view, cells, colour);
}

void Canvas::tubes(const Rect& viewport, const std::vector<Tube>& tubes, const std::vector<Facet>& facets,
                   const Camera& camera, const Light& light, int sides) {
    gl_backend::tubes(*this, viewport, tubes, facets, camera, light, sides);
}

void Canvas::clip(const Rect& box) {
    const PixelBox p = clip_box(box);
    bind();
    glEnable(GL_SCISSOR_TEST);
    glScissor(p.x0, height_ - p.y1, p.x1 - p.x0, p.y1 - p.y0);  // GL counts rows from the bottom
}

void Canvas::unclip() { glDisable(GL_SCISSOR_TEST); }

}  // namespace render
