#pragma once
// A formula run's last step as Ready writes its own pattern files (--format
// vti): VTK XML ImageData with the <RD> element that holds the rule and its
// parameters, apply_when_loading="false", so Ready, ParaView and figgen
// continue from it. An output: the command writes it from the state a
// scene hands over; scenes/ cannot include it.

#include <string>

#include "ready/state.hpp"

namespace ready {

// The file's text: VTK XML ImageData, version 1.0, UInt64 headers, binary
// zlib-compressed blocks of 32 KiB, as VTK 9's writer makes Ready's files.
std::string ready_vti(const ReadyState& state);

}  // namespace ready
