#include "render/vector/vector.hpp"

#include "base/module.hpp"

namespace render::vector {
namespace {
constexpr base::ModuleSpec spec{FIGGEN_VECTOR_RELATIVE,          FIGGEN_VECTOR_BUILT, "figgen_vector_api", api_version,
                                "vector module for PDF and SVG", "libcairo2"};
}  // namespace

const Api& api() {
    return base::module_of<Api, spec>().api();
}
void preload() {
    base::module_of<Api, spec>().preload();
}

}  // namespace render::vector
