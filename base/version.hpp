#pragma once
// figgen's version, from project(VERSION) in CMakeLists.txt: written into
// every output's metadata, a parts manifest and the gallery's page.

namespace base {

const char* version();

}  // namespace base
