#pragma once
// Where one of figgen's run-time modules is (the video module, the MPI
// module: libraries opened with dlopen only by the processes that need
// them): installed beside the program, `relative` to the running
// executable's folder (as `cmake --install` puts it), else where this build
// made it, `built`. Never a path from the environment or a description.

#include <filesystem>

namespace render {

std::filesystem::path module_path(const char* relative, const char* built);

}  // namespace render
