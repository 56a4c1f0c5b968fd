#pragma once
namespace app {
// figgen's version, from project(VERSION) in CMakeLists.txt; written into every output's metadata.
inline const char* version() { return FIGGEN_VERSION; }
}  // namespace app
