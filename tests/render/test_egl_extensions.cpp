// Which EGL offers the device platform figgen draws on with --gl
// egl-device: the client extension strings of NVIDIA's driver (580.159, as
// read on an H200 node) and of Debian 12's Mesa 22.3.
#include <catch2/catch.hpp>

#include "render/gl/gl_library.hpp"

using render::detail::has_device_platform;
using render::detail::has_extension;

namespace {

// NVIDIA names EGL_EXT_device_base: device query and enumeration together.
constexpr const char* nvidia =
    "EGL_EXT_platform_base EGL_EXT_device_base EGL_KHR_client_get_all_proc_addresses EGL_EXT_client_extensions "
    "EGL_KHR_debug EGL_KHR_platform_x11 EGL_EXT_platform_x11 EGL_EXT_platform_device "
    "EGL_MESA_platform_surfaceless EGL_EXT_explicit_device";
// Mesa names the two separately.
constexpr const char* mesa =
    "EGL_EXT_device_base EGL_EXT_device_enumeration EGL_EXT_device_query EGL_EXT_platform_base "
    "EGL_KHR_client_get_all_proc_addresses EGL_EXT_client_extensions EGL_KHR_debug EGL_EXT_platform_device "
    "EGL_EXT_platform_wayland EGL_KHR_platform_wayland EGL_EXT_platform_x11 EGL_KHR_platform_x11 "
    "EGL_EXT_platform_xcb EGL_MESA_platform_gbm EGL_KHR_platform_gbm EGL_MESA_platform_surfaceless";

}  // namespace

TEST_CASE("the device platform is found in NVIDIA's and Mesa's client extensions", "[gl]") {
    CHECK(has_device_platform(nvidia));
    CHECK(has_device_platform(mesa));
    CHECK(has_device_platform("EGL_EXT_device_enumeration EGL_EXT_device_query EGL_EXT_platform_device"));
}

TEST_CASE("the device platform is refused without enumeration, query or the platform", "[gl]") {
    CHECK_FALSE(has_device_platform(nullptr));
    CHECK_FALSE(has_device_platform(""));
    CHECK_FALSE(has_device_platform("EGL_EXT_platform_device"));                           // no devices to list
    CHECK_FALSE(has_device_platform("EGL_EXT_device_base"));                               // no platform
    CHECK_FALSE(has_device_platform("EGL_EXT_device_enumeration EGL_EXT_platform_device"));  // no query
    CHECK_FALSE(has_device_platform("EGL_EXT_device_query EGL_EXT_platform_device"));        // no enumeration
    // Whole names only: a longer name that starts or ends the same is another extension.
    CHECK_FALSE(has_device_platform("EGL_EXT_device_base_x EGL_EXT_platform_device"));
    CHECK_FALSE(has_device_platform("EGL_EXT_device_base EGL_EXT_platform_devices"));
    CHECK_FALSE(has_device_platform("XEGL_EXT_device_base EGL_EXT_platform_device"));
}

TEST_CASE("extension names are matched whole, anywhere in the string", "[gl]") {
    CHECK(has_extension("A B C", "A"));
    CHECK(has_extension("A B C", "B"));
    CHECK(has_extension("A B C", "C"));
    CHECK_FALSE(has_extension("AB BC", "B"));
    CHECK(has_extension("AB B", "B"));
    CHECK_FALSE(has_extension(nullptr, "A"));
}
