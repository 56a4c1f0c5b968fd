#include "app/describe.hpp"

#include <cstdio>
#include <sstream>
#include <utility>

#include "app/terminal_text.hpp"
#include "description/description.hpp"
#include "scenes/scene.hpp"
#include "sim/check.hpp"

namespace app {
using description::Description;
using description::Key;
using description::SettingsLog;
namespace {

struct Reading {
    std::vector<SettingsLog::Section> sections;
    std::vector<sim::CheckedRange> ranges;
};

// The scene's phase 1 for `d`: every setting it reads and every range its
// model checks. Nothing runs. A description the scene refuses stops there,
// and what it read until then is listed.
Reading read_settings(const Description& d) {
    Reading reading;
    SettingsLog log;
    sim::RangeLog ranges;
    try {
        scenes::read_scene(d, scenes::SceneOptions{1.0, false});
    } catch (const description::UsageError&) {  // a SettingError, or a scene that cannot go on without a setting
    }
    reading.sections = log.sections;
    reading.ranges = ranges.ranges();
    return reading;
}

std::string shown(const nlohmann::json& value) {
    if (value.is_null()) return "-";
    if (value.is_number_float()) {
        char number[32];
        std::snprintf(number, sizeof number, "%.6g", value.get<double>());
        return number;
    }
    return fit_columns(value.is_string() ? "\"" + value.get<std::string>() + "\"" : value.dump(), 28);
}

// The range the model checks `key` against, and where its bound comes from ("" for none).
std::pair<std::string, std::string> range_of(const std::string& key, const std::vector<sim::CheckedRange>& ranges) {
    for (const auto& r : ranges) {
        if (r.name != key) continue;
        char text[96];
        std::snprintf(text, sizeof text, r.integer ? "an integer from %.0f to %.0f" : "from %g to %g", r.low, r.high);
        return {text, r.why};
    }
    return {"", ""};
}

const SettingsLog::Section* find(const std::vector<SettingsLog::Section>& sections, const std::string& name) {
    for (const auto& s : sections)
        if (s.name == name) return &s;
    return nullptr;
}

}  // namespace

std::string describe(const std::filesystem::path& file) {
    SettingsLog top;  // the description's own sections, read by load_description
    const Description d = description::load_description(file);
    const Reading own = read_settings(d);

    std::ostringstream out;
    out << d.id << ": " << d.title << "\n"
        << "  source: " << d.source << "\n"
        << "  scene: " << d.scene << ", seed " << d.seed << ", described in " << file.string() << "\n";
    if (!d.original_caption.empty())
        out << "  original caption" << (d.language.empty() ? "" : " (" + d.language + ")") << ": " << d.original_caption
            << "\n";
    // Columns by display width: a value in Chinese takes two columns a character.
    auto row = [&](const std::string& key, const std::string& value, const std::string& fallback,
                   const std::string& allowed, const std::string& meaning) {
        out << "  " << pad_columns(key, 20) << " " << pad_columns(value, 28) << " " << pad_columns(fallback, 28) << " "
            << pad_columns(allowed, 30) << " " << meaning << "\n";
    };
    // Each key as its schema declares it (scenes/: description/schema.hpp):
    // its default, and what it allows where the declaration states it; else
    // the range a ranged read or the model checked.
    auto section = [&](const SettingsLog::Section& s, const std::vector<sim::CheckedRange>& ranges) {
        out << "\n[" << s.name << "]\n";
        row("key", "this figure", "default", "allowed", "meaning");
        for (const Key& key : s.keys) {
            const nlohmann::json value = s.used.contains(key.name) ? s.used[key.name] : nlohmann::json();
            const auto [range, why] = range_of(key.name, ranges);
            std::string allowed = !key.allowed.empty()        ? key.allowed
                                  : s.allowed.count(key.name) ? s.allowed.at(key.name)
                                  : !range.empty()            ? range
                                                              : key.type;
            if (allowed.empty()) allowed = "see meaning";
            row(key.name, shown(value), shown(key.fallback), allowed,
                why.empty() ? key.help : key.help + " (" + why + ")");
        }
    };
    for (const auto& s : own.sections) section(s, own.ranges);
    for (const char* name : {"figure", "animation"})
        if (const auto* s = find(top.sections, name)) section(*s, {});
    out << "\nChange any of them with --set key=value ([params]) or --set section.key=value.\n";
    return out.str();
}

}  // namespace app
