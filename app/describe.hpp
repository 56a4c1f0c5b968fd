#pragma once
// `figgen describe ID`: every setting a figure's scene reads, with the
// figure's value, its default, what it allows and what it means. The keys,
// defaults and meanings are the scene's schema (description/schema.hpp);
// the values and the ranges the model checks come from running the scene
// once as far as it reads its settings (SettingsLog, sim::RangeLog).

#include <filesystem>
#include <string>

namespace app {

// The text `figgen describe` prints for the description in `file`.
std::string describe(const std::filesystem::path& file);

}  // namespace app
