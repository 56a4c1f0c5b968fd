#pragma once
// A model's own check of its parameters (sim's validate(), require_*),
// seen as a check of the description's settings: a parameter the model
// refuses becomes the SettingError of the key the user wrote.

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "description/schema.hpp"
#include "scenes/description_names.hpp"

namespace scenes {

// The model's name of a parameter -> the key read from the section, where they differ.
using KeyNames = std::vector<std::pair<std::string, std::string>>;

// Runs `check`; a sim::ParameterError it throws becomes the SettingError of
// `section`'s key named in `names` (else the key of the model's own name).
void check_model(Settings& section, const std::function<void()>& check, const KeyNames& names = {});

// A schema's check that runs the model's own, P::validate(), after its keys are read.
template <class P>
typename description::Schema<P>::Check validated(const KeyNames& names = {}) {
    return [names](Settings& section, const std::string&, P& p) {
        check_model(
            section, [&] { p.validate(); }, names);
    };
}
// The same for the parameters `at(value)` finds in what the schema reads.
template <class At>
auto validated(const KeyNames& names, At at) {
    return [names, at](Settings& section, const std::string&, auto& value) {
        check_model(
            section, [&] { at(value).validate(); }, names);
    };
}

}  // namespace scenes
