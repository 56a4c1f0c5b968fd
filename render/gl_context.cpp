#include "render/gl_context.hpp"

#include <stdexcept>

namespace render {

GlContext& GlContext::get() {
    static GlContext context;  // once per process, destroyed after main returns
    return context;
}

GlContext::GlContext() : buffer_(4 * 4 * 4) {
    const int attribs[] = {
        OSMESA_FORMAT,                OSMESA_RGBA,
        OSMESA_DEPTH_BITS,            0,
        OSMESA_STENCIL_BITS,          0,
        OSMESA_ACCUM_BITS,            0,
        OSMESA_PROFILE,               OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, 3,
        OSMESA_CONTEXT_MINOR_VERSION, 3,
        0,
    };
    context_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!context_) throw std::runtime_error("OSMesa: cannot create a core-profile 3.3 context");
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 4, 4)) {
        OSMesaDestroyContext(context_);
        throw std::runtime_error("OSMesa: cannot make the context current");
    }
    // Rows top to bottom, as images are stored everywhere else.
    OSMesaPixelStore(OSMESA_Y_UP, 0);
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples_);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_size_);
}

GlContext::~GlContext() {
    if (context_) OSMesaDestroyContext(context_);
}

void check_gl(const char* what) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR)
        throw std::runtime_error("OpenGL error " + std::to_string(error) + " in " + what);
}

}  // namespace render
