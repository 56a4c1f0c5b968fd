#pragma once
// The process's one OpenGL context: OSMesa (llvmpipe), core profile 3.3 or
// later, no window, no GPU. Created on first use, destroyed at exit.
// Every drawing class calls GlContext::get() before touching GL.
//
// libOSMesa (and LLVM with it) is not linked: it is opened when a command
// is about to draw, so commands and inputs that draw nothing never pay for it.

#include <string>
#include <vector>

#include "render/gl.hpp"

namespace render {

// The most cells a side of a field the renderer draws as one texture:
// GL 4.5's least GL_MAX_TEXTURE_SIZE, so a description is checked against
// it without opening GL. GlContext refuses a context with less.
constexpr int max_texture_side = 16384;

// Starts opening the GL library on a thread of its own, so that the work
// before the first drawing overlaps with it. Call it once the command knows
// it will draw; calling it again, or never, is harmless. GlContext::get()
// waits for it.
void preload_gl();

class GlContext {
public:
    static GlContext& get();

    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    const std::string& renderer() const { return renderer_; }  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    const std::string& version() const { return version_; }    // GL_VERSION
    int max_samples() const { return max_samples_; }           // GL_MAX_SAMPLES
    int max_texture_size() const { return max_texture_size_; } // GL_MAX_TEXTURE_SIZE: a field's most cells a side

private:
    GlContext();
    ~GlContext();

    void* context_ = nullptr;            // the OSMesaContext
    std::vector<unsigned char> buffer_;  // tiny default framebuffer: all drawing goes to FBOs
    std::string renderer_;
    std::string version_;
    int max_samples_ = 0;
    int max_texture_size_ = 0;
};

// Throws std::runtime_error naming `what` if GL has recorded an error.
void check_gl(const char* what);

}  // namespace render
