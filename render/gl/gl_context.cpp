#include "render/gl/gl_context.hpp"

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

#include "base/background.hpp"
#include "render/gl/gl_library.hpp"

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
// auto, EGL's surfaceless platform), or why none.
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
    case GlPlatform::automatic:  // GlContext::make() goes on from here
        opened.library = detail::open_egl(-1, opened.passed_over);
        break;
    }
    return opened;
}

base::Background<Opened>& loader() {
    static base::Background<Opened> l(open_chosen);
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
    if (!automatic) {
        if (!opened.library) throw std::runtime_error(opened.why);
        use(std::move(opened.library));
        return;
    }
    // auto: llvmpipe wherever it can be had, else the GPU, said in one line.
    // 1. EGL's surfaceless platform, when Mesa gives llvmpipe there.
    std::string egl_why = opened.passed_over, gpu;
    if (opened.library) {
        try {
            use(std::move(opened.library));
            if (is_llvmpipe(renderer_)) return;
            gpu = renderer_;
            egl_why = "EGL's surfaceless platform draws with " + renderer_ + ", not llvmpipe";
        } catch (const std::runtime_error& e) {
            egl_why = e.what();
        }
        library_.reset();  // EGL's context released before another is made
    }
    // 2. OSMesa.
    std::string osmesa_why;
    if (std::unique_ptr<detail::GlLibrary> osmesa = detail::open_osmesa(osmesa_why)) {
        try {
            use(std::move(osmesa));
            fallback_ = egl_why;
            std::fprintf(stderr, "figgen: note: drawing with OSMesa: %s\n", fallback_.c_str());
            return;
        } catch (const std::runtime_error& e) {
            osmesa_why = e.what();
            library_.reset();
        }
    }
    // Without libEGL there is nothing more to try.
    std::string egl_missing;
    if (!detail::egl_loads(egl_missing)) throw std::runtime_error("no GL: EGL: " + egl_why + "; OSMesa: " + osmesa_why);
    // 3. Mesa's software device on EGL's device platform.
    std::string device_why;
    if (std::unique_ptr<detail::GlLibrary> software = detail::open_egl_software(device_why)) {
        try {
            use(std::move(software));
            if (is_llvmpipe(renderer_)) {
                fallback_ = egl_why + "; OSMesa: " + osmesa_why;
                std::fprintf(stderr, "figgen: note: drawing with EGL's software device: %s\n", fallback_.c_str());
                return;
            }
            device_why = "it draws with " + renderer_;
        } catch (const std::runtime_error& e) {
            device_why = e.what();
        }
        library_.reset();
    }
    // 4. No llvmpipe: the GPU, through EGL's surfaceless platform where it
    // gave one, else the device platform's first device.
    const std::string no_llvmpipe =
        "EGL: " + egl_why + "; OSMesa: " + osmesa_why + "; EGL's software device: " + device_why;
    std::string gpu_why;
    std::unique_ptr<detail::GlLibrary> library = detail::open_egl(gpu.empty() ? 0 : -1, gpu_why);
    if (!library) throw std::runtime_error("no GL: " + no_llvmpipe + "; EGL's first device: " + gpu_why);
    try {
        use(std::move(library));
    } catch (const std::runtime_error& e) {
        throw std::runtime_error("no GL: " + no_llvmpipe + "; EGL's " + (gpu.empty() ? "first device" : "GPU") +
                                 ": " + e.what());
    }
    fallback_ = no_llvmpipe;
    std::fprintf(stderr, "figgen: note: drawing with %s (%s), not llvmpipe, which is not to be had: %s\n",
                 renderer_.c_str(), platform_.c_str(), fallback_.c_str());
}

namespace {

// FIGGEN_GL_DEBUG=1: a debug context, its messages synchronous, and the
// first GL error or high-severity message kept for check_gl to throw.
bool debug_wanted() {
    const char* value = std::getenv("FIGGEN_GL_DEBUG");
    return value && std::string(value) == "1";
}

struct DebugLog {
    std::mutex lock;
    std::string first;  // the first error or high-severity message; empty when none
};

DebugLog& debug_log() {
    static DebugLog log;
    return log;
}

void GLAD_API_PTR on_debug_message(GLenum /*source*/, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                   const GLchar* message, const void* /*user*/) {
    if (type != GL_DEBUG_TYPE_ERROR && severity != GL_DEBUG_SEVERITY_HIGH) return;
    const std::string text = length >= 0 ? std::string(message, static_cast<std::size_t>(length)) : message;
    DebugLog& log = debug_log();
    std::lock_guard<std::mutex> hold(log.lock);
    if (log.first.empty())
        log.first = std::string(type == GL_DEBUG_TYPE_ERROR ? "GL error" : "high-severity GL message") + " " +
                    std::to_string(id) + ": " + text;
}

}  // namespace

// Makes `library`'s context current and resolves GL through it.
void GlContext::use(std::unique_ptr<detail::GlLibrary> library) {
    library_ = std::move(library);
    debug_ = debug_wanted();
    library_->make_current(debug_);
    const auto resolve = [](void* lib, const char* name) {
        return static_cast<detail::GlLibrary*>(lib)->function(name);
    };
    // The entry points of the version the context has, and no more: glad
    // leaves those of a later version null, and figgen calls none of them.
    if (gladLoadGLUserPtr(resolve, library_.get()) == 0)
        throw std::runtime_error(library_->platform() + ": cannot resolve the OpenGL core functions");
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    platform_ = library_->platform();
    device_ = library_->device();
    const std::string gl = "OpenGL " + version_ + " (" + renderer_ + ", " + platform_ + ")";
    if (!GLAD_GL_VERSION_3_3)
        throw std::runtime_error(gl + " is older than the OpenGL 3.3 core profile that figgen needs");
    if (debug_) {
        if (!GLAD_GL_KHR_debug)
            throw std::runtime_error("FIGGEN_GL_DEBUG=1: " + gl + " has no KHR_debug to report its errors through");
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);  // on the calling thread, inside the call at fault
        glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
        glDebugMessageCallback(on_debug_message, nullptr);
    }
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples_);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_size_);
    if (max_texture_size_ < max_texture_side)
        throw std::runtime_error(gl + " draws textures of at most " + std::to_string(max_texture_size_) +
                                 " texels a side; figgen needs " + std::to_string(max_texture_side));
    if (max_samples_ < canvas_samples)
        throw std::runtime_error(gl + " draws at most " + std::to_string(max_samples_) +
                                 " samples a pixel; figgen needs " + std::to_string(canvas_samples));
    check_gl("setting up the context");
}

GlContext::~GlContext() = default;

void check_gl(const char* what) {
    std::string reported;
    {
        DebugLog& log = debug_log();
        std::lock_guard<std::mutex> hold(log.lock);
        reported.swap(log.first);
    }
    const GLenum error = glGetError();
    if (!reported.empty()) {
        while (glGetError() != GL_NO_ERROR) {
        }
        throw std::runtime_error("FIGGEN_GL_DEBUG=1: " + reported + " (by " + what + ")");
    }
    if (error != GL_NO_ERROR)
        throw std::runtime_error("OpenGL error " + std::to_string(error) + " in " + what);
}

}  // namespace render
