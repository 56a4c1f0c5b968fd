#include "base/version.hpp"

namespace base {

// FIGGEN_VERSION is defined for this file alone (base/CMakeLists.txt), so
// that a new version recompiles one file.
const char* version() {
    return FIGGEN_VERSION;
}

}  // namespace base
