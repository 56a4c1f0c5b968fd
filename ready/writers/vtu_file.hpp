#pragma once
// A mesh run's last step as Ready writes its mesh pattern files (--format
// vtu): VTK XML UnstructuredGrid, the chemicals as cell data a, b, ...,
// with the <RD> element of the rule, apply_when_loading="false", so Ready,
// ParaView and figgen continue from it. An output, as vti_file.hpp.

#include <string>

#include "ready/state.hpp"

namespace ready {

// The file's text (ready/vtu.hpp's write_vtu: UInt64 headers, binary
// zlib-compressed blocks). Throws std::invalid_argument where the state
// has no mesh or its chemicals do not hold a value a cell.
std::string ready_vtu(const ReadyState& state);

}  // namespace ready
