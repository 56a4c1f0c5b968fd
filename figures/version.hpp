#pragma once
namespace figures {
const char* version();  // figgen's version, written into every output's metadata
}
