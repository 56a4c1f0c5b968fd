#pragma once
// The description reader's names that the scenes use unqualified.
#include "description/description.hpp"
#include "description/schema.hpp"

namespace scenes {
using description::Animation;
using description::Description;
using description::expand;
using description::format_step;
using description::integers_allowed;
using description::Key;
using description::names_allowed;
using description::numbers_allowed;
using description::Schema;
using description::SettingError;
using description::Settings;
using description::SettingsLog;
using description::UsageError;
}  // namespace scenes
