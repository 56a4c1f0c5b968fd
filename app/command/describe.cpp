#include "app/command/describe.hpp"

#include "app/render/targets.hpp"

#include <cstdio>
#include <sstream>
#include <utility>

#include "app/render/terminal_text.hpp"
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
    if (!value.is_string()) return fit_columns(value.dump(), 28);
    std::string quoted = "\"";  // appended in steps: GCC 12 warns falsely (-Wrestrict) on "\"" + std::string
    quoted += value.get<std::string>();
    quoted += '"';
    return fit_columns(quoted, 28);
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

Described describe_figure(const Description& d, const std::vector<SettingsLog::Section>& own_sections) {
    const Reading own = read_settings(d);
    Described out{d.id, d.title, d.source, d.scene, d.file.string(), d.seed, d.original_caption, d.language, {}};
    // Each key as its schema (scenes: description/schema.hpp) declares it:
    // its default, and what it allows where the declaration states it;
    // else the range a ranged read or the model checked.
    auto section = [&](const SettingsLog::Section& s, const std::vector<sim::CheckedRange>& ranges) {
        DescribedSection described{s.name, {}};
        for (const Key& key : s.keys) {
            const auto [range, why] = range_of(key.name, ranges);
            std::string allowed = !key.allowed.empty()        ? key.allowed
                                  : s.allowed.count(key.name) ? s.allowed.at(key.name)
                                  : !range.empty()            ? range
                                                              : key.type;
            described.keys.push_back({key.name, s.used.contains(key.name) ? s.used[key.name] : nlohmann::json(),
                                      key.fallback, allowed, why.empty() ? key.help : key.help + " (" + why + ")"});
        }
        out.sections.push_back(std::move(described));
    };
    for (const auto& s : own.sections) section(s, own.ranges);
    for (const char* name : {"figure", "animation"})
        if (const auto* s = find(own_sections, name)) section(*s, {});
    return out;
}

Described describe_figure(const std::string& target) {
    SettingsLog top;  // the description's own sections, read as it is loaded
    const Description d = load_target(target, {}, std::nullopt, false);
    return describe_figure(d, top.sections);
}

std::string describe(const std::string& target) {
    const Described d = describe_figure(target);
    std::ostringstream out;
    out << d.id << ": " << d.title << "\n"
        << "  source: " << d.source << "\n"
        << "  scene: " << d.scene << ", seed " << d.seed << ", described in " << d.file << "\n";
    if (!d.original_caption.empty())
        out << "  original caption" << (d.language.empty() ? "" : " (" + d.language + ")") << ": " << d.original_caption
            << "\n";
    // Columns by display width: a value in Chinese takes two columns a character.
    auto row = [&](const std::string& key, const std::string& value, const std::string& fallback,
                   const std::string& allowed, const std::string& meaning) {
        out << "  " << pad_columns(key, 20) << " " << pad_columns(value, 28) << " " << pad_columns(fallback, 28) << " "
            << pad_columns(allowed, 30) << " " << meaning << "\n";
    };
    for (const DescribedSection& s : d.sections) {
        out << "\n[" << s.name << "]\n";
        row("key", "this figure", "default", "allowed", "meaning");
        for (const DescribedKey& k : s.keys)
            row(k.key, shown(k.value), shown(k.fallback), k.allowed.empty() ? "see meaning" : k.allowed, k.meaning);
    }
    out << "\nChange any of them with --set key=value ([params]) or --set section.key=value.\n";
    return out.str();
}

}  // namespace app
