#pragma once
// What a command's FIGURE names: a catalog id, a description file, or one
// of Ready's pattern files (.vti in any case; a mesh, .vtu, is refused as
// not yet run), read into the Description every command works from.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "description/description.hpp"

namespace app {

// Reads `target` with the --set `overrides` and `seed`. A pattern's stored
// arrays are decoded only `with_arrays` (a render needs them; describe
// and convert do not). Throws UsageError naming what is wrong.
description::Description load_target(const std::string& target, const std::vector<std::string>& overrides = {},
                                     std::optional<std::uint64_t> seed = std::nullopt, bool with_arrays = true);

}  // namespace app
