#pragma once
// `figgen describe ID`: every setting a figure's scene reads, with the
// figure's value, the model's default, the range the model checks and what
// it means. Found by running the scene only as far as it reads its settings
// (twice: with the description's [params] and [style], and with them empty,
// for the defaults), noting each key read (SettingsLog) and each range
// checked (sim::RangeLog): the listing cannot drift from the code.

#include <filesystem>
#include <string>

namespace app {

// The text `figgen describe` prints for the description in `file`.
std::string describe(const std::filesystem::path& file);

}  // namespace app
