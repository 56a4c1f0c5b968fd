#pragma once
// Where one of figgen's run-time modules is (the video module, the MPI
// module: libraries opened with dlopen only by the processes that need
// them): installed beside the program, `relative` to the running
// executable's folder (as `cmake --install` puts it), else where this build
// made it, `built`. Never a path from the environment or a description.

#include <filesystem>
#include <stdexcept>
#include <string>

#include "base/background.hpp"

namespace base {

std::filesystem::path module_path(const char* relative, const char* built);

// The folder the program runs from: the executable's, unless the program
// that embeds figgen (the Python module) says where figgen is installed.
// An installed figgen's modules and descriptions are found from it.
std::filesystem::path program_folder();
void set_program_folder(const std::filesystem::path& folder);

// One of figgen's modules: where it is, its entry point (an extern "C"
// function returning its Api, a struct whose first member is an int
// version), the version this build expects, and for messages what it does
// and which Debian packages its libraries come from.
struct ModuleSpec {
    const char* relative;
    const char* built;
    const char* entry;
    int version;
    const char* what;      // "video module"
    const char* packages;  // "libavcodec59, libavformat59 and libswscale6"
    // Its symbols visible to the libraries it opens in turn (RTLD_GLOBAL):
    // Open MPI's components need libmpi's.
    bool global = false;
};

// The module's Api, or null and one line saying why not.
struct OpenedModule {
    const void* api = nullptr;
    std::string error;
};
// Opens it (dlopen, RTLD_LOCAL) and checks its version; a module of another build is closed again.
OpenedModule open_module(const ModuleSpec& spec);

// A module's Api, opened on a thread of its own by preload() (while the
// first model runs) or at the first api(), which waits for it. Keep one in
// a function-local static.
template <typename Api>
class LoadedModule {
public:
    explicit LoadedModule(OpenedModule (*open)()) : loader_(open) {}
    // Throws std::runtime_error with the one line saying why it could not be opened.
    const Api& api() {
        const OpenedModule& opened = loader_.get();
        if (!opened.api) throw std::runtime_error(opened.error);
        return *static_cast<const Api*>(opened.api);
    }
    void preload() { loader_.start(); }

private:
    Background<OpenedModule> loader_;
};

// The module `spec` names, one LoadedModule for the process.
template <typename Api, const ModuleSpec& spec>
LoadedModule<Api>& module_of() {
    static LoadedModule<Api> module([] { return open_module(spec); });
    return module;
}

}  // namespace base
