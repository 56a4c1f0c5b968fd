#include "render/gl_context.hpp"

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

#include "render/background.hpp"
#include "render/gl_library.hpp"

namespace render {
namespace {

struct Chosen {
    std::mutex lock;
    std::optional<GlChoice> choice;  // set by choose_gl() or, on first use, from FIGGEN_GL
};

Chosen& chosen() {
    static Chosen c;
    return c;
}

GlChoice the_choice() {
    Chosen& c = chosen();
    std::lock_guard<std::mutex> hold(c.lock);
    if (!c.choice) {
        GlChoice choice;
        if (const char* name = std::getenv("FIGGEN_GL"); name && *name) {
            const std::optional<GlPlatform> platform = gl_platform_of(name);
            if (!platform)
                throw std::runtime_error("FIGGEN_GL=" + std::string(name) + " is not allowed: use " +
                                         gl_platforms_allowed());
            choice.platform = *platform;
        }
        c.choice = choice;
    }
    return *c.choice;
}

// What the loading thread opened: the library of the chosen platform (for
// auto, EGL's surfaceless platform, else OSMesa), or why none.
struct Opened {
    mutable std::unique_ptr<detail::GlLibrary> library;  // taken by GlContext
    std::string why;          // when there is no library
    std::string passed_over;  // auto: why EGL was not opened
};

Opened open_chosen() {
    Opened opened;
    GlChoice choice;
    try {
        choice = the_choice();
    } catch (const std::runtime_error& e) {
        opened.why = e.what();
        return opened;
    }
    switch (choice.platform) {
    case GlPlatform::osmesa:
        opened.library = detail::open_osmesa(opened.why);
        break;
    case GlPlatform::egl:
        opened.library = detail::open_egl(-1, opened.why);
        break;
    case GlPlatform::egl_device:
        opened.library = detail::open_egl(choice.device, opened.why);
        break;
    case GlPlatform::automatic:
        opened.library = detail::open_egl(-1, opened.passed_over);
        if (!opened.library) opened.library = detail::open_osmesa(opened.why);
        break;
    }
    return opened;
}

Background<Opened>& loader() {
    static Background<Opened> l(open_chosen);
    return l;
}

}  // namespace

const std::vector<std::string>& gl_platform_names() {
    static const std::vector<std::string> names = {"auto", "osmesa", "egl", "egl-device"};
    return names;
}

std::optional<GlPlatform> gl_platform_of(const std::string& name) {
    const std::vector<std::string>& names = gl_platform_names();
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return static_cast<GlPlatform>(i);
    return std::nullopt;
}

std::string gl_platforms_allowed() {
    const std::vector<std::string>& names = gl_platform_names();
    std::string allowed;
    for (std::size_t i = 0; i < names.size(); ++i)
        allowed += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return allowed;
}

void choose_gl(GlChoice choice) {
    Chosen& c = chosen();
    std::lock_guard<std::mutex> hold(c.lock);
    c.choice = choice;
}

std::optional<std::string> check_gl_choice(GlChoice choice) {
    if (choice.platform != GlPlatform::egl_device) return std::nullopt;
    std::string why;
    const int devices = detail::count_egl_devices(why);
    if (devices < 0) return "--gl egl-device: " + why;
    if (choice.device >= devices)
        return "--gl-device " + std::to_string(choice.device) + " is not allowed: EGL's device platform has " +
               std::to_string(devices) + " device" + (devices == 1 ? "" : "s") + " here (0.." +
               std::to_string(devices - 1) + ")";
    return std::nullopt;
}

void preload_gl() {
    loader().start();
}

GlContext& GlContext::get() {
    static GlContext context;  // once per process, destroyed after main returns
    return context;
}

GlContext::GlContext() {
    // A failure is final: the library it took is gone, so a later get()
    // says the first reason again.
    static std::string failed;
    if (!failed.empty()) throw std::runtime_error(failed);
    try {
        make();
    } catch (const std::runtime_error& e) {
        failed = e.what();
        library_.reset();
        throw;
    }
}

void GlContext::make() {
    const Opened& opened = loader().get();
    const bool automatic = the_choice().platform == GlPlatform::automatic;
    if (!opened.library)
        throw std::runtime_error(automatic ? "no GL: EGL: " + opened.passed_over + "; OSMesa: " + opened.why
                                           : opened.why);
    std::unique_ptr<detail::GlLibrary> library = std::move(opened.library);
    fallback_ = opened.passed_over;
    if (!automatic || library->platform() == "osmesa") {
        use(std::move(library), false);
    } else {
        try {
            use(std::move(library), true);
        } catch (const std::runtime_error& e) {
            library_.reset();  // EGL's context released before OSMesa's is made
            fallback_ = e.what();
            std::string why;
            std::unique_ptr<detail::GlLibrary> osmesa = detail::open_osmesa(why);
            if (!osmesa) throw std::runtime_error("no GL: EGL: " + fallback_ + "; OSMesa: " + why);
            use(std::move(osmesa), false);
        }
    }
    if (!fallback_.empty()) std::fprintf(stderr, "figgen: note: drawing with OSMesa: %s\n", fallback_.c_str());
}

// Makes `library`'s context current and resolves GL through it; with
// `want_llvmpipe`, refuses any other renderer.
void GlContext::use(std::unique_ptr<detail::GlLibrary> library, bool want_llvmpipe) {
    library_ = std::move(library);
    library_->make_current();
    const auto resolve = [](void* lib, const char* name) {
        return static_cast<detail::GlLibrary*>(lib)->function(name);
    };
    // The entry points of the version the context has.
    if (gladLoadGLUserPtr(resolve, library_.get()) == 0)
        throw std::runtime_error(library_->platform() + ": cannot resolve the OpenGL core functions");
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    platform_ = library_->platform();
    device_ = library_->device();
    if (want_llvmpipe && !is_llvmpipe(renderer_))
        throw std::runtime_error("EGL's surfaceless platform draws with " + renderer_ +
                                 ", not llvmpipe, and --gl auto takes a software renderer (--gl egl takes it, "
                                 "LIBGL_ALWAYS_SOFTWARE=1 makes EGL take llvmpipe)");
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples_);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_size_);
    const std::string gl = "OpenGL " + version_ + " (" + renderer_ + ", " + platform_ + ")";
    if (max_texture_size_ < max_texture_side)
        throw std::runtime_error(gl + " draws textures of at most " + std::to_string(max_texture_size_) +
                                 " texels a side; figgen needs " + std::to_string(max_texture_side));
    if (max_samples_ < canvas_samples)
        throw std::runtime_error(gl + " draws at most " + std::to_string(max_samples_) +
                                 " samples a pixel; figgen needs " + std::to_string(canvas_samples));
}

GlContext::~GlContext() = default;

void check_gl(const char* what) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR)
        throw std::runtime_error("OpenGL error " + std::to_string(error) + " in " + what);
}

}  // namespace render
