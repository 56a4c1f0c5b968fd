#include "render/media.hpp"

#include <dlfcn.h>

#include <stdexcept>
#include <system_error>

#include "render/background.hpp"
#include "render/module.hpp"

namespace render::media {
namespace {

struct Opened {
    const Api* api = nullptr;
    std::string error;  // why not, when api is null
};

Opened open_module() {
    const std::filesystem::path path = module_path(FIGGEN_MEDIA_RELATIVE, FIGGEN_MEDIA_BUILT);
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
