#pragma once
// The process's one OpenGL context: OSMesa (llvmpipe), core profile 3.3 or
// later, no window, no GPU. Created on first use, destroyed at exit.
// Every drawing class calls GlContext::get() before touching GL.

#include <string>
#include <vector>

#include "render/gl.hpp"

namespace render {

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

    OSMesaContext context_ = nullptr;
    std::vector<unsigned char> buffer_;  // tiny default framebuffer: all drawing goes to FBOs
    std::string renderer_;
    std::string version_;
    int max_samples_ = 0;
    int max_texture_size_ = 0;
};

// Throws std::runtime_error naming `what` if GL has recorded an error.
void check_gl(const char* what);

}  // namespace render
