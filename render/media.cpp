#include "render/media.hpp"

#include <stdexcept>

#include "render/background.hpp"
#include "render/module.hpp"

namespace render::media {
namespace {

OpenedModule open() {
    return open_module({FIGGEN_MEDIA_RELATIVE, FIGGEN_MEDIA_BUILT, "figgen_media_api", api_version, "video module",
                        "libavcodec59, libavformat59 and libswscale6"});
}

Background<OpenedModule>& loader() {
    static Background<OpenedModule> l(open);
    return l;
}

}  // namespace

const Api& api() {
    const OpenedModule& opened = loader().get();
    if (!opened.api) throw std::runtime_error(opened.error);
    return *static_cast<const Api*>(opened.api);
}

void preload() {
    loader().start();
}

}  // namespace render::media
