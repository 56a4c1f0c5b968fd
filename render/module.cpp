#include "render/module.hpp"

#include <system_error>

namespace render {

std::filesystem::path module_path(const char* relative, const char* built) {
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        const std::filesystem::path installed = exe.parent_path() / relative;
        if (std::filesystem::is_regular_file(installed, error)) return installed;
    }
    return built;
}

}  // namespace render
