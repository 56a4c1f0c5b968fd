// EGL without a display: Mesa's surfaceless platform (llvmpipe, or the
// GPU Mesa finds), or the device platform of EGL_EXT_platform_device (a
// headless NVIDIA node, or Mesa's software device). libEGL.so.1 is
// libglvnd's dispatcher: it opens the vendor library (Mesa's, NVIDIA's)
// that the vendor files under /usr/share/glvnd/egl_vendor.d name.
#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "render/gl/gl_library.hpp"

// Khronos's headers for the types, constants and function-pointer types;
// no EGL function is called by name: they come from dlsym and
// eglGetProcAddress.
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>

namespace render::detail {
namespace {

constexpr const char* library_name = "libEGL.so.1";
constexpr const char* library_package = "libegl1";
constexpr const char* mesa_package = "libegl-mesa0";

std::string error_name(EGLint error) {
    static const struct {
        EGLint code;
        const char* name;
    } names[] = {
        {EGL_NOT_INITIALIZED, "EGL_NOT_INITIALIZED"}, {EGL_BAD_ACCESS, "EGL_BAD_ACCESS"},
        {EGL_BAD_ALLOC, "EGL_BAD_ALLOC"},             {EGL_BAD_ATTRIBUTE, "EGL_BAD_ATTRIBUTE"},
        {EGL_BAD_CONFIG, "EGL_BAD_CONFIG"},           {EGL_BAD_CONTEXT, "EGL_BAD_CONTEXT"},
        {EGL_BAD_DISPLAY, "EGL_BAD_DISPLAY"},         {EGL_BAD_MATCH, "EGL_BAD_MATCH"},
        {EGL_BAD_PARAMETER, "EGL_BAD_PARAMETER"},     {EGL_BAD_SURFACE, "EGL_BAD_SURFACE"},
        {EGL_CONTEXT_LOST, "EGL_CONTEXT_LOST"},
    };
    for (const auto& n : names)
        if (n.code == error) return n.name;
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04x", static_cast<unsigned>(error));
    return hex;
}

// The EGL functions figgen calls, from libEGL.so.1.
struct Egl {
    PFNEGLGETPROCADDRESSPROC get_proc_address = nullptr;
    PFNEGLGETERRORPROC get_error = nullptr;
    PFNEGLQUERYSTRINGPROC query_string = nullptr;
    PFNEGLGETPLATFORMDISPLAYPROC get_platform_display = nullptr;
    PFNEGLINITIALIZEPROC initialize = nullptr;
    PFNEGLBINDAPIPROC bind_api = nullptr;
    PFNEGLCHOOSECONFIGPROC choose_config = nullptr;
    PFNEGLCREATECONTEXTPROC create_context = nullptr;
    PFNEGLDESTROYCONTEXTPROC destroy_context = nullptr;
    PFNEGLMAKECURRENTPROC make_current = nullptr;
    PFNEGLRELEASETHREADPROC release_thread = nullptr;
    // EGL_EXT_device_enumeration and EGL_EXT_device_query, or EGL_EXT_device_base
    PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
    PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;

    // The library opened and its core functions resolved; false, with `why`, when not.
    bool open(std::string& why) {
        void* handle = ::dlopen(library_name, RTLD_NOW | RTLD_LOCAL);  // never closed
        if (!handle) {
            why = "cannot load " + std::string(library_name) + " (" + ::dlerror() + "): install Debian's " +
                  library_package + " and " + mesa_package;
            return false;
        }
        bool all = true;
        const auto resolve = [&](auto& function, const char* name) {
            function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(::dlsym(handle, name));
            if (!function && all) {
                why = std::string(library_name) + " has no " + name + " (EGL 1.5): install Debian's " +
                      library_package;
                all = false;
            }
        };
        resolve(get_proc_address, "eglGetProcAddress");
        resolve(get_error, "eglGetError");
        resolve(query_string, "eglQueryString");
        resolve(get_platform_display, "eglGetPlatformDisplay");
        resolve(initialize, "eglInitialize");
        resolve(bind_api, "eglBindAPI");
        resolve(choose_config, "eglChooseConfig");
        resolve(create_context, "eglCreateContext");
        resolve(destroy_context, "eglDestroyContext");
        resolve(make_current, "eglMakeCurrent");
        resolve(release_thread, "eglReleaseThread");
        if (!all) return false;
        query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(get_proc_address("eglQueryDevicesEXT"));
        query_device_string =
            reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(get_proc_address("eglQueryDeviceStringEXT"));
        return true;
    }

    std::string last_error() const { return error_name(get_error()); }

    // The devices of the device platform; empty, with `why`, when it has none.
    std::vector<EGLDeviceEXT> devices(std::string& why) const {
        const char* client = query_string(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!query_devices || !has_device_platform(client)) {
            why = "this EGL has no device platform (EGL_EXT_platform_device): install Debian's " +
                  std::string(mesa_package) + ", or the GPU driver's EGL";
            return {};
        }
        EGLint count = 0;
        if (!query_devices(0, nullptr, &count) || count <= 0) {
            why = "EGL's device platform finds no device";
            return {};
        }
        std::vector<EGLDeviceEXT> list(static_cast<std::size_t>(count));
        if (!query_devices(count, list.data(), &count)) {
            why = "eglQueryDevicesEXT failed (" + last_error() + ")";
            return {};
        }
        list.resize(static_cast<std::size_t>(count));
        return list;
    }

    // A device's DRM node, "software" for Mesa's software device.
    std::string device_name(EGLDeviceEXT device) const {
        if (!query_device_string) return "unnamed";
        const char* extensions = query_device_string(device, EGL_EXTENSIONS);
        if (has_extension(extensions, "EGL_MESA_device_software")) return "software";
        if (has_extension(extensions, "EGL_EXT_device_drm"))
            if (const char* file = query_device_string(device, EGL_DRM_DEVICE_FILE_EXT)) return file;
        return "unnamed";
    }
};

class EglLibrary final : public GlLibrary {
public:
    EglLibrary(const Egl& egl, EGLDisplay display, std::string platform, std::string device)
        : egl_(egl), display_(display), platform_(std::move(platform)), device_(std::move(device)) {}

    // The context is released and destroyed; the display is left
    // initialized, as the library stays loaded: eglTerminate would unload
    // Mesa's driver (dlclose) while what it allocated for the process is
    // still held, and the process ends soon after anyway.
    ~EglLibrary() override {
        if (context_ != EGL_NO_CONTEXT) {
            egl_.make_current(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            egl_.destroy_context(display_, context_);
        }
        egl_.release_thread();
    }

    void make_current(bool debug) override {
        const std::string where = "EGL (" + platform_ + ")";
        if (!egl_.bind_api(EGL_OPENGL_API))
            throw std::runtime_error(where + " has no desktop OpenGL (eglBindAPI: " + egl_.last_error() + ")");
        const char* extensions = egl_.query_string(display_, EGL_EXTENSIONS);
        if (!has_extension(extensions, "EGL_KHR_surfaceless_context"))
            throw std::runtime_error(where + " cannot draw without a surface (no EGL_KHR_surfaceless_context)");
        // No config where the display allows it: every drawing goes to
        // framebuffer objects, which need none.
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
            const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
            EGLint found = 0;
            if (!egl_.choose_config(display_, wanted, &config, 1, &found) || found < 1)
                throw std::runtime_error(where + " offers no OpenGL config");
        }
        // GL 3.3 core: the version whose entry points figgen calls (a
        // driver may give a later one; NVIDIA's gives exactly this).
        const EGLint attributes[] = {
            EGL_CONTEXT_MAJOR_VERSION,       3,
            EGL_CONTEXT_MINOR_VERSION,       3,
            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
            debug ? EGL_CONTEXT_OPENGL_DEBUG : EGL_NONE, EGL_TRUE,
            EGL_NONE,
        };
        context_ = egl_.create_context(display_, config, EGL_NO_CONTEXT, attributes);
        if (context_ == EGL_NO_CONTEXT)
            throw std::runtime_error(where + ": cannot create a core-profile 3.3 context (" + egl_.last_error() +
                                     ")");
        if (!egl_.make_current(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            throw std::runtime_error(where + ": cannot make the context current (" + egl_.last_error() + ")");
    }

    GLADapiproc function(const char* name) const override {
        return reinterpret_cast<GLADapiproc>(egl_.get_proc_address(name));
    }

    std::string platform() const override { return platform_; }
    std::string device() const override { return device_; }

private:
    Egl egl_;
    EGLDisplay display_;
    EGLContext context_ = EGL_NO_CONTEXT;
    std::string platform_;
    std::string device_;
};

}  // namespace

bool has_extension(const char* extensions, const char* name) {
    if (!extensions) return false;
    const std::size_t length = std::strlen(name);
    for (const char* p = extensions; (p = std::strstr(p, name)) != nullptr; p += length)
        if ((p == extensions || p[-1] == ' ') && (p[length] == ' ' || p[length] == '\0')) return true;
    return false;
}

bool has_device_platform(const char* client) {
    const bool enumeration = has_extension(client, "EGL_EXT_device_base") ||
                             (has_extension(client, "EGL_EXT_device_enumeration") &&
                              has_extension(client, "EGL_EXT_device_query"));
    return enumeration && has_extension(client, "EGL_EXT_platform_device");
}

std::unique_ptr<GlLibrary> open_egl(int device, std::string& why) {
    Egl egl;
    if (!egl.open(why)) return nullptr;
    EGLDisplay display = EGL_NO_DISPLAY;
    std::string device_name;
    if (device < 0) {
        const char* client = egl.query_string(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!has_extension(client, "EGL_MESA_platform_surfaceless")) {
            why = "this EGL has no surfaceless platform (EGL_MESA_platform_surfaceless): install Debian's " +
                  std::string(mesa_package);
            return nullptr;
        }
        display = egl.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    } else {
        const std::vector<EGLDeviceEXT> devices = egl.devices(why);
        if (devices.empty()) return nullptr;
        if (device >= static_cast<int>(devices.size())) {
            why = "--gl-device " + std::to_string(device) + ": EGL's device platform has " +
                  std::to_string(devices.size()) + " device" + (devices.size() == 1 ? "" : "s") + " (0.." +
                  std::to_string(devices.size() - 1) + ")";
            return nullptr;
        }
        device_name = egl.device_name(devices[static_cast<std::size_t>(device)]);
        display = egl.get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(device)],
                                           nullptr);
    }
    const std::string platform = device < 0 ? "egl" : "egl-device";
    if (display == EGL_NO_DISPLAY) {
        why = "EGL (" + platform + ") has no display (" + egl.last_error() + "): install Debian's " + mesa_package;
        return nullptr;
    }
    EGLint major = 0, minor = 0;
    if (!egl.initialize(display, &major, &minor)) {
        why = "EGL (" + platform + ") cannot start its driver (" + egl.last_error() +
              "): install Debian's libgl1-mesa-dri, or the GPU driver";
        return nullptr;
    }
    return std::make_unique<EglLibrary>(egl, display, platform, device_name);
}

bool egl_loads(std::string& why) {
    Egl egl;
    return egl.open(why);
}

std::unique_ptr<GlLibrary> open_egl_software(std::string& why) {
    Egl egl;
    if (!egl.open(why)) return nullptr;
    const std::vector<EGLDeviceEXT> devices = egl.devices(why);
    for (std::size_t i = 0; i < devices.size(); ++i)
        if (egl.device_name(devices[i]) == "software") return open_egl(static_cast<int>(i), why);
    if (!devices.empty()) why = "EGL's device platform has no software device (EGL_MESA_device_software)";
    return nullptr;
}

int count_egl_devices(std::string& why) {
    Egl egl;
    if (!egl.open(why)) return -1;
    const std::vector<EGLDeviceEXT> devices = egl.devices(why);
    return devices.empty() ? -1 : static_cast<int>(devices.size());
}

}  // namespace render::detail
