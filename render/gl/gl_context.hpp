#pragma once
// The process's one OpenGL context: core profile 3.3 or later (refused
// when the driver gives less), no window,
// from OSMesa or EGL (surfaceless, or a device such as a headless GPU).
// Created on first use, destroyed at exit. Every drawing class calls
// GlContext::get() before touching GL.
//
// No GL library (nor LLVM behind Mesa's) is linked: the one chosen is
// opened when a command is about to draw, so commands and inputs that draw
// nothing never pay for it.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/field.hpp"
#include "render/gl/gl.hpp"

namespace render {

namespace detail {
class GlLibrary;
}

// The most cells a side of a field (render/field.hpp's max_texture_side):
// GlContext refuses a context with less.

// Samples per pixel of every multisampled canvas: always 4, whatever more
// the GL offers (Mesa 25.3's llvmpipe offers 8), so the pixels do not change
// with the machine. GlContext refuses a context with fewer.
constexpr int canvas_samples = 4;

// Where the context comes from (--gl, FIGGEN_GL).
enum class GlPlatform {
    automatic,   // "auto": llvmpipe (EGL surfaceless, OSMesa, EGL's software device), else the GPU, saying why
    osmesa,      // "osmesa": libOSMesa
    egl,         // "egl": EGL's surfaceless platform (Mesa), llvmpipe or the GPU Mesa finds
    egl_device,  // "egl-device": EGL's device platform, device GlChoice::device
};
struct GlChoice {
    GlPlatform platform = GlPlatform::automatic;
    int device = 0;  // egl-device: which device, in EGL_EXT_device_enumeration's order
};
// The names --gl accepts, in GlPlatform's order.
const std::vector<std::string>& gl_platform_names();
std::optional<GlPlatform> gl_platform_of(const std::string& name);
// "auto, osmesa, egl or egl-device": what a refusal of a name says is allowed.
std::string gl_platforms_allowed();
// Whether a GL_RENDERER is Mesa's llvmpipe, the renderer the goldens are made with.
inline bool is_llvmpipe(const std::string& renderer) { return renderer.rfind("llvmpipe", 0) == 0; }
// Chooses the platform: before preload_gl() or GlContext::get(), which
// otherwise take FIGGEN_GL from the environment (or auto).
void choose_gl(GlChoice choice);
// For egl-device: the device asked for exists. Opens EGL (not its driver)
// to count them; the reason in one line when not. Nothing for the others.
std::optional<std::string> check_gl_choice(GlChoice choice);

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
    const std::string& platform() const { return platform_; }  // "osmesa", "egl" or "egl-device"
    const std::string& device() const { return device_; }      // egl-device: its DRM node or "software"
    // Why auto passed over EGL's surfaceless llvmpipe; empty when it did not.
    const std::string& fallback() const { return fallback_; }
    // A debug context (FIGGEN_GL_DEBUG=1), whose errors check_gl throws.
    bool debug() const { return debug_; }
    int max_samples() const { return max_samples_; }           // GL_MAX_SAMPLES
    int max_texture_size() const { return max_texture_size_; } // GL_MAX_TEXTURE_SIZE: a field's most cells a side

private:
    GlContext();
    ~GlContext();

    void make();
    void use(std::unique_ptr<detail::GlLibrary> library);

    std::unique_ptr<detail::GlLibrary> library_;  // the one whose context is current
    std::string renderer_;
    std::string version_;
    std::string platform_;
    std::string device_;
    std::string fallback_;
    int max_samples_ = 0;
    int max_texture_size_ = 0;
    bool debug_ = false;
};

// Throws std::runtime_error naming `what` if GL has recorded an error or,
// in a debug context, reported an error or a high-severity message.
void check_gl(const char* what);

}  // namespace render
