#include "scenes/model_check.hpp"

#include "sim/check.hpp"

namespace scenes {

void check_model(Settings& section, const std::function<void()>& check, const KeyNames& names) {
    try {
        check();
    } catch (const sim::ParameterError& e) {
        std::string key = e.name;
        for (const auto& [model_name, written] : names)
            if (model_name == e.name) key = written;
        section.refuse(key, e.value, e.allowed);
    }
}

}  // namespace scenes
