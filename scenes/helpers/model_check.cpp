#include "scenes/helpers/model_check.hpp"

#include "sim/check.hpp"

namespace scenes {

namespace {
std::string written_name(const std::string& model_name, const KeyNames& names) {
    for (const auto& [name, written] : names)
        if (name == model_name) return written;
    return model_name;
}
}  // namespace

void check_model(Settings& section, const std::function<void()>& check, const KeyNames& names) {
    std::vector<sim::CheckedRange> ranges;
    try {
        sim::RangeLog log;  // the ranges the model checks, noted again under the keys' names
        check();
        ranges = log.ranges();
    } catch (const sim::ParameterError& e) {
        section.refuse(written_name(e.name, names), e.value, e.allowed);
    }
    for (sim::CheckedRange range : ranges) {
        range.name = written_name(range.name, names);
        sim::RangeLog::note(range);
    }
}

}  // namespace scenes
