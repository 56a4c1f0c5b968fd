#include "render/media.hpp"

#include <dlfcn.h>

#include <stdexcept>
#include <system_error>

#include "render/background.hpp"

namespace render::media {
namespace {

// Where the module is: installed beside the program (FIGGEN_MEDIA_RELATIVE,
// from the folder of the running executable, as `cmake --install` puts
// it), else where this build made it (FIGGEN_MEDIA_BUILT). Never a path from
// the environment or a description.
std::filesystem::path module_path() {
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        const std::filesystem::path installed = exe.parent_path() / FIGGEN_MEDIA_RELATIVE;
        if (std::filesystem::is_regular_file(installed, error)) return installed;
    }
    return FIGGEN_MEDIA_BUILT;
}

struct Opened {
    const Api* api = nullptr;
    std::string error;  // why not, when api is null
};

Opened open_module() {
    const std::filesystem::path path = module_path();
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle)
        return {nullptr, "cannot load figgen's video module (" + std::string(::dlerror()) +
                             "): build figgen again (make) or install it again; its FFmpeg libraries are Debian's "
                             "libavcodec59, libavformat59 and libswscale6"};
    auto* entry = reinterpret_cast<const Api* (*)()>(::dlsym(handle, "figgen_media_api"));
    const Api* api = entry ? entry() : nullptr;
    if (!api || api->version != api_version) {
        ::dlclose(handle);  // not ours to keep loaded
        return {nullptr, path.string() +
                             (entry ? " is from another build of figgen" : " is not figgen's video module") +
                             ": build or install figgen again"};
    }
    return {api, {}};
}

Background<Opened>& loader() {
    static Background<Opened> l(open_module);
    return l;
}

}  // namespace

const Api& api() {
    const Opened& opened = loader().get();
    if (!opened.api) throw std::runtime_error(opened.error);
    return *opened.api;
}

void preload() {
    loader().start();
}

}  // namespace render::media
