#pragma once
// Inside render/: the libraries a GL context can come from, opened at run
// time (dlopen). gl_context.cpp picks one (--gl); gl_osmesa.cpp and
// gl_egl.cpp open them. Nothing here is linked against a GL library.

#include <memory>
#include <string>

#include "render/gl/gl.hpp"

namespace render::detail {

// A GL library opened, with its display initialized where it has one. It
// is opened on the loading thread (the slow part: Mesa's driver and LLVM);
// make_current() then runs on the thread that draws.
class GlLibrary {
public:
    virtual ~GlLibrary() = default;

    // Makes a core-profile context of GL 3.3 or later current on this
    // thread, with no window, a debug context when `debug`;
    // std::runtime_error says why not.
    virtual void make_current(bool debug) = 0;
    // A GL function of the current context, for glad's loader.
    virtual GLADapiproc function(const char* name) const = 0;
    // What the JSON records: "osmesa", "egl" or "egl-device".
    virtual std::string platform() const = 0;
    // The device an egl-device context draws on (e.g. "/dev/dri/renderD128",
    // or "software"), empty elsewhere.
    virtual std::string device() const { return {}; }
};

// Null, with `why` in one line that names the Debian package to install
// when a library is missing, when the library or its display cannot be
// opened.
std::unique_ptr<GlLibrary> open_osmesa(std::string& why);
// EGL's surfaceless platform (Mesa's), or with `device` >= 0 its device
// platform on that device (EGL_EXT_device_enumeration's order).
std::unique_ptr<GlLibrary> open_egl(int device, std::string& why);
// Whether libEGL.so.1 loads with the functions figgen calls; `why` when not.
bool egl_loads(std::string& why);
// Mesa's software device (EGL_MESA_device_software) on EGL's device
// platform; null, with `why`, when there is none.
std::unique_ptr<GlLibrary> open_egl_software(std::string& why);
// How many devices EGL's device platform offers; -1, with `why`, when it
// cannot say.
int count_egl_devices(std::string& why);

// Whether a space-separated extension string names `name`.
bool has_extension(const char* extensions, const char* name);
// Whether EGL's client extensions offer the device platform figgen uses:
// EGL_EXT_platform_device with device enumeration and query, which
// EGL_EXT_device_base stands for (NVIDIA names only it) as well as
// EGL_EXT_device_enumeration with EGL_EXT_device_query (Mesa).
bool has_device_platform(const char* client_extensions);

}  // namespace render::detail
