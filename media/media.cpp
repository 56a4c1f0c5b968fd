#include "media/media.hpp"

#include "base/module.hpp"

namespace render::media {
namespace {
constexpr base::ModuleSpec spec{FIGGEN_MEDIA_RELATIVE, FIGGEN_MEDIA_BUILT,
                                "figgen_media_api",    api_version,
                                "video module",        "libavcodec59, libavformat59 and libswscale6"};
}  // namespace

const Api& api() {
    return base::module_of<Api, spec>().api();
}
void preload() {
    base::module_of<Api, spec>().preload();
}

}  // namespace render::media
