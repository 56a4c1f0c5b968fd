#include "render/gl_context.hpp"

#include <dlfcn.h>

#include <stdexcept>

#include "render/background.hpp"

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

namespace render {
namespace {

// Debian 12's libosmesa6 (Mesa's llvmpipe); its soname since Mesa 10.
constexpr const char* osmesa_library = "libOSMesa.so.8";
constexpr const char* osmesa_package = "libosmesa6";

// The library, opened once; `error` says why not when it is null.
struct Library {
    void* handle = nullptr;
    std::string error;
};

Library open_library() {
    Library library;
    // RTLD_NOW: every symbol bound here, on the preloading thread, not on
    // the first call of each later.
    library.handle = ::dlopen(osmesa_library, RTLD_NOW | RTLD_LOCAL);
    if (!library.handle) library.error = ::dlerror();
    return library;
}

Background<Library>& loader() {
    static Background<Library> l(open_library);
    return l;
}

template <typename Function>
Function* symbol(const Library& lib, const char* name) {
    void* address = ::dlsym(lib.handle, name);
    if (!address)
        throw std::runtime_error(std::string(osmesa_library) + " has no " + name + ": reinstall Debian's " +
                                 osmesa_package);
    return reinterpret_cast<Function*>(address);
}

struct OsMesa {
    decltype(OSMesaCreateContextAttribs)* create_context_attribs;
    decltype(OSMesaMakeCurrent)* make_current;
    decltype(OSMesaDestroyContext)* destroy_context;
    decltype(OSMesaPixelStore)* pixel_store;
    decltype(OSMesaGetProcAddress)* get_proc_address;
};

const OsMesa& osmesa() {
    static const OsMesa functions = [] {
        const Library& lib = loader().get();
        if (!lib.handle)
            throw std::runtime_error("cannot load " + std::string(osmesa_library) + " (" + lib.error +
                                     "): install Debian's " + osmesa_package);
        return OsMesa{symbol<decltype(OSMesaCreateContextAttribs)>(lib, "OSMesaCreateContextAttribs"),
                      symbol<decltype(OSMesaMakeCurrent)>(lib, "OSMesaMakeCurrent"),
                      symbol<decltype(OSMesaDestroyContext)>(lib, "OSMesaDestroyContext"),
                      symbol<decltype(OSMesaPixelStore)>(lib, "OSMesaPixelStore"),
                      symbol<decltype(OSMesaGetProcAddress)>(lib, "OSMesaGetProcAddress")};
    }();
    return functions;
}

GLADapiproc gl_function(const char* name) {
    return reinterpret_cast<GLADapiproc>(osmesa().get_proc_address(name));
}

}  // namespace

void preload_gl() {
    loader().start();
}

GlContext& GlContext::get() {
    static GlContext context;  // once per process, destroyed after main returns
    return context;
}

GlContext::GlContext() : buffer_(4 * 4 * 4) {
    const OsMesa& os = osmesa();
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
    OSMesaContext context = os.create_context_attribs(attribs, nullptr);
    if (!context) throw std::runtime_error("OSMesa: cannot create a core-profile 3.3 context");
    if (!os.make_current(context, buffer_.data(), GL_UNSIGNED_BYTE, 4, 4)) {
        os.destroy_context(context);
        throw std::runtime_error("OSMesa: cannot make the context current");
    }
    context_ = context;
    // The entry points of the version the context has, through OSMesa.
    if (gladLoadGL(gl_function) == 0) {
        os.destroy_context(context);
        context_ = nullptr;
        throw std::runtime_error("OSMesa: cannot resolve the OpenGL core functions");
    }
    // Rows top to bottom, as images are stored everywhere else.
    os.pixel_store(OSMESA_Y_UP, 0);
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples_);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_size_);
    if (max_texture_size_ < max_texture_side) {
        os.destroy_context(context);
        context_ = nullptr;
        throw std::runtime_error("OpenGL " + version_ + " (" + renderer_ + ") draws textures of at most " +
                                 std::to_string(max_texture_size_) + " texels a side; figgen needs " +
                                 std::to_string(max_texture_side));
    }
}

GlContext::~GlContext() {
    if (context_) osmesa().destroy_context(static_cast<OSMesaContext>(context_));
}

void check_gl(const char* what) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR)
        throw std::runtime_error("OpenGL error " + std::to_string(error) + " in " + what);
}

}  // namespace render
