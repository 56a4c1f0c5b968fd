#include "base/module.hpp"

#include <dlfcn.h>

#include <mutex>
#include <system_error>

namespace base {

namespace {
std::mutex folder_lock;
std::filesystem::path given_folder;
}  // namespace

void set_program_folder(const std::filesystem::path& folder) {
    std::lock_guard<std::mutex> hold(folder_lock);
    given_folder = folder;
}

std::filesystem::path program_folder() {
    {
        std::lock_guard<std::mutex> hold(folder_lock);
        if (!given_folder.empty()) return given_folder;
    }
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    return error ? std::filesystem::path() : exe.parent_path();
}

std::filesystem::path module_path(const char* relative, const char* built) {
    const std::filesystem::path folder = program_folder();
    std::error_code error;
    if (!folder.empty()) {
        const std::filesystem::path installed = folder / relative;
        if (std::filesystem::is_regular_file(installed, error)) return installed;
    }
    return built;
}

OpenedModule open_module(const ModuleSpec& spec) {
    const std::filesystem::path path = module_path(spec.relative, spec.built);
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | (spec.global ? RTLD_GLOBAL : RTLD_LOCAL));
    if (!handle)
        return {nullptr, std::string("cannot load figgen's ") + spec.what + " (" + ::dlerror() +
                             "): build figgen again (make) or install it again; its libraries are Debian's " +
                             spec.packages};
    auto* entry = reinterpret_cast<const void* (*)()>(::dlsym(handle, spec.entry));
    const void* api = entry ? entry() : nullptr;
    if (!api || *static_cast<const int*>(api) != spec.version) {
        ::dlclose(handle);  // not ours to keep loaded
        return {nullptr, path.string() + (entry ? " is from another build of figgen" : " is not figgen's " +
                                                                                            std::string(spec.what)) +
                             ": build or install figgen again"};
    }
    return {api, {}};
}

}  // namespace base
