#pragma once
// `figgen describe ID`: every setting a figure's scene reads, with the
// figure's value, its default, what it allows and what it means. The keys,
// defaults and meanings are the scene's schema (description/schema.hpp);
// the values and the ranges the model checks come from running the scene
// once as far as it reads its settings (SettingsLog, sim::RangeLog).

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "description/description.hpp"

namespace app {

// One setting of a figure: its key, the figure's value and the default (null
// for none), what it allows (empty: see its meaning), and its meaning.
struct DescribedKey {
    std::string key;
    nlohmann::json value, fallback;
    std::string allowed, meaning;
};
struct DescribedSection {
    std::string name;  // "params", "style", "params.plants[0]", "figure", "animation"
    std::vector<DescribedKey> keys;
};
struct Described {
    std::string id, title, source, scene, file;
    std::uint64_t seed;
    std::string original_caption, language;
    std::vector<DescribedSection> sections;
};

// Every setting of the figure `target` names (a catalog id, a description
// file or a Ready pattern), as data (the Python module's describe()).
Described describe_figure(const std::string& target);
// The same for a description already read; `own_sections` are its [figure]
// and [animation] as load_description read them (a SettingsLog around it).
Described describe_figure(const description::Description& d,
                          const std::vector<description::SettingsLog::Section>& own_sections);

// The text `figgen describe` prints for the figure `target` names.
std::string describe(const std::string& target);

}  // namespace app
