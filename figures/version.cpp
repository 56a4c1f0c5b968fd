#include "figures/version.hpp"
namespace figures {
const char* version() {
    return "0.1.0";
}
}  // namespace figures
