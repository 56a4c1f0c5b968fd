// OSMesa (Mesa's off-screen library, llvmpipe): a context drawing into a
// buffer of ours. Mesa removed it upstream in 25.1; Debian 12 and 13 still
// ship it as libosmesa6.
#include <dlfcn.h>

#include <stdexcept>
#include <vector>

#include "render/gl/gl_library.hpp"

// OSMesa's header for its types, constants and prototypes; glad's gl.h,
// included first, stands in for the <GL/gl.h> it includes (and its GLAPI
// macros). No OSMesa function is called by name: they come from dlsym.
#ifndef GLAPI
#define GLAPI extern
#endif
#ifndef GLAPIENTRY
#define GLAPIENTRY
#endif
#include <GL/osmesa.h>

namespace render::detail {
namespace {

// Debian 12's libosmesa6 (Mesa's llvmpipe); its soname since Mesa 10.
constexpr const char* library_name = "libOSMesa.so.8";
constexpr const char* package = "libosmesa6";

class OsMesa final : public GlLibrary {
public:
    explicit OsMesa(void* handle)
        : create_context_attribs_(symbol<decltype(OSMesaCreateContextAttribs)>(handle, "OSMesaCreateContextAttribs")),
          make_current_(symbol<decltype(OSMesaMakeCurrent)>(handle, "OSMesaMakeCurrent")),
          destroy_context_(symbol<decltype(OSMesaDestroyContext)>(handle, "OSMesaDestroyContext")),
          pixel_store_(symbol<decltype(OSMesaPixelStore)>(handle, "OSMesaPixelStore")),
          get_proc_address_(symbol<decltype(OSMesaGetProcAddress)>(handle, "OSMesaGetProcAddress")) {}

    ~OsMesa() override {
        if (context_) destroy_context_(context_);
    }

    // OSMesa has no debug flag: its contexts report through KHR_debug
    // once GL_DEBUG_OUTPUT is on, which GlContext turns on.
    void make_current(bool /*debug*/) override {
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
        context_ = create_context_attribs_(attribs, nullptr);
        if (!context_) throw std::runtime_error("OSMesa: cannot create a core-profile 3.3 context");
        // A tiny default framebuffer: all drawing goes to framebuffer objects.
        if (!make_current_(context_, buffer_.data(), GL_UNSIGNED_BYTE, 4, 4))
            throw std::runtime_error("OSMesa: cannot make the context current");
        pixel_store_(OSMESA_Y_UP, 0);
    }

    GLADapiproc function(const char* name) const override {
        return reinterpret_cast<GLADapiproc>(get_proc_address_(name));
    }

    std::string platform() const override { return "osmesa"; }

private:
    template <typename Function>
    static Function* symbol(void* handle, const char* name) {
        void* address = ::dlsym(handle, name);
        if (!address)
            throw std::runtime_error(std::string(library_name) + " has no " + name + ": reinstall Debian's " +
                                     package);
        return reinterpret_cast<Function*>(address);
    }

    decltype(OSMesaCreateContextAttribs)* create_context_attribs_;
    decltype(OSMesaMakeCurrent)* make_current_;
    decltype(OSMesaDestroyContext)* destroy_context_;
    decltype(OSMesaPixelStore)* pixel_store_;
    decltype(OSMesaGetProcAddress)* get_proc_address_;
    OSMesaContext context_ = nullptr;
    std::vector<unsigned char> buffer_ = std::vector<unsigned char>(4 * 4 * 4);
};

}  // namespace

std::unique_ptr<GlLibrary> open_osmesa(std::string& why) {
    // RTLD_NOW: every symbol bound here, on the loading thread, not on the
    // first call of each later. Never closed: LLVM's static objects are
    // destroyed at exit.
    void* handle = ::dlopen(library_name, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        why = "cannot load " + std::string(library_name) + " (" + ::dlerror() + "): install Debian's " + package;
        return nullptr;
    }
    try {
        return std::make_unique<OsMesa>(handle);
    } catch (const std::runtime_error& e) {
        why = e.what();
        return nullptr;
    }
}

}  // namespace render::detail
