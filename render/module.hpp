#pragma once
// Where one of figgen's run-time modules is (the video module, the MPI
// module: libraries opened with dlopen only by the processes that need
// them): installed beside the program, `relative` to the running
// executable's folder (as `cmake --install` puts it), else where this build
// made it, `built`. Never a path from the environment or a description.

#include <filesystem>
#include <string>

namespace render {

std::filesystem::path module_path(const char* relative, const char* built);

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
};

// The module's Api, or null and one line saying why not.
struct OpenedModule {
    const void* api = nullptr;
    std::string error;
};
// Opens it (dlopen, RTLD_LOCAL) and checks its version; a module of another build is closed again.
OpenedModule open_module(const ModuleSpec& spec);

}  // namespace render
