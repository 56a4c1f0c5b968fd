#include "render/vector.hpp"

#include <stdexcept>

#include "render/background.hpp"
#include "render/module.hpp"

namespace render::vector {
namespace {

OpenedModule open() {
    return open_module({FIGGEN_VECTOR_RELATIVE, FIGGEN_VECTOR_BUILT, "figgen_vector_api", api_version, "vector module for PDF and SVG",
                        "libcairo2"});
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

}  // namespace render::vector
