#include "app/render/targets.hpp"

#include "description/catalog.hpp"
#include "description/plain_name.hpp"
#include "ready/pattern.hpp"

namespace app {

description::Description load_target(const std::string& target, const std::vector<std::string>& overrides,
                                     std::optional<std::uint64_t> seed, bool with_arrays) {
    switch (ready::file_kind(target)) {
    case ready::FileKind::image:
    case ready::FileKind::mesh: return ready::load_pattern(target, overrides, seed, with_arrays);
    case ready::FileKind::none: break;
    }
    return description::load_description(description::resolve_figure(target), overrides, seed);
}

}  // namespace app
