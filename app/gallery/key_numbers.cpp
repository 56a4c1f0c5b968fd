#include "app/gallery/key_numbers.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>

#include "scenes/scene.hpp"

namespace app {
namespace {

using scenes::KeyNumber;
using scenes::KeyReference;

// ---- reading the metadata -------------------------------------------------

const nlohmann::json* child(const nlohmann::json& node, const std::string& step) {
    if (node.is_object()) {
        const auto found = node.find(step);
        return found == node.end() ? nullptr : &*found;
    }
    if (node.is_array() && !step.empty() && step.size() <= 9 &&
        step.find_first_not_of("0123456789") == std::string::npos) {
        const std::size_t index = std::stoul(step);
        return index < node.size() ? &node[index] : nullptr;
    }
    return nullptr;
}

std::vector<std::string> steps_of(const std::string& path) {
    std::vector<std::string> steps;
    for (std::size_t at = 1; at <= path.size();) {
        const std::size_t next = std::min(path.find('/', at), path.size());
        steps.push_back(path.substr(at, next - at));
        at = next + 1;
    }
    return steps;
}

// The value `path` leads to in `meta`, or null.
const nlohmann::json* at_pointer(const nlohmann::json& meta, const std::string& path) {
    const nlohmann::json* node = &meta;
    for (const std::string& step : steps_of(path))
        if (!(node = child(*node, step))) return nullptr;
    return node;
}

// A value `path` reached, with the concrete pointer and the array element
// its last "*" went through (for {field} labels and conditions).
struct Found {
    const nlohmann::json* value;
    std::string pointer;
    const nlohmann::json* element;
    std::size_t index;  // the element's place in its array
};

void expand(const nlohmann::json& node, const std::vector<std::string>& steps, std::size_t at,
            const std::string& pointer, const nlohmann::json* element, std::size_t index, std::vector<Found>& found) {
    if (at == steps.size()) {
        found.push_back({&node, pointer, element, index});
        return;
    }
    if (steps[at] == "*") {
        if (!node.is_array()) return;
        for (std::size_t i = 0; i < node.size() && i < 1000; ++i)
            expand(node[i], steps, at + 1, pointer + "/" + std::to_string(i), &node[i], i, found);
        return;
    }
    if (const nlohmann::json* next = child(node, steps[at]))
        expand(*next, steps, at + 1, pointer + "/" + steps[at], element, index, found);
}

// Whether one test "field=value", "field=a|b" or "!field" holds.
bool test_holds(const std::string& test, const nlohmann::json& meta, const nlohmann::json* element) {
    const bool absent = !test.empty() && test[0] == '!';
    const std::size_t eq = test.find('=');
    const std::string field = test.substr(absent ? 1 : 0, eq == std::string::npos ? std::string::npos : eq - absent);
    const nlohmann::json* value =
        !field.empty() && field[0] == '/' ? at_pointer(meta, field) : (element ? child(*element, field) : nullptr);
    if (absent) return value == nullptr;
    if (!value || eq == std::string::npos) return false;
    const std::string wanted = test.substr(eq + 1);
    for (std::size_t at = 0; at <= wanted.size();) {
        const std::size_t bar = std::min(wanted.find('|', at), wanted.size());
        const std::string one = wanted.substr(at, bar - at);
        at = bar + 1;
        if (value->is_string() && value->get<std::string>() == one) return true;
        if (value->is_number()) {
            const double a = value->get<double>(), b = std::strtod(one.c_str(), nullptr);
            if (std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b))) return true;
        }
    }
    return false;
}

// Whether every test of `condition` (joined by ",") holds; "" always does.
bool holds(const char* condition, const nlohmann::json& meta, const nlohmann::json* element) {
    const std::string text = condition;
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t comma = std::min(text.find(',', at), text.size());
        if (!test_holds(text.substr(at, comma - at), meta, element)) return false;
        at = comma + 1;
    }
    return true;
}

// `label` with its {field}, {#} and {field|text} filled in for `element`,
// the `index`th of its array.
std::string label_of(const std::string& label, const nlohmann::json* element, std::size_t index) {
    std::string text;
    for (std::size_t at = 0; at < label.size();) {
        const std::size_t open = label.find('{', at);
        const std::size_t close = open == std::string::npos ? open : label.find('}', open);
        if (close == std::string::npos) {
            text += label.substr(at);
            break;
        }
        text += label.substr(at, open - at);
        std::string field = label.substr(open + 1, close - open - 1), shown_if_present;
        if (const std::size_t bar = field.find('|'); bar != std::string::npos) {
            shown_if_present = field.substr(bar + 1);
            field.resize(bar);
        }
        const nlohmann::json* value = element ? child(*element, field) : nullptr;
        if (field == "#")
            text += std::to_string(index + 1);
        else if (!shown_if_present.empty())
            text += value ? shown_if_present : "";
        else if (value && value->is_string() && value->get<std::string>().size() <= 80)
            text += value->get<std::string>();
        else if (value && value->is_number()) {
            char number[32];  // as a person writes it: q = 0.6, rule 18
            std::snprintf(number, sizeof number, "%.6g", value->get<double>());
            text += number;
        }
        else
            text += "?";
        at = close + 1;
    }
    return text;
}

bool finite_number(const nlohmann::json* value) {
    return value && value->is_number() && std::isfinite(value->get<double>());
}

// "value ± error", both at the error's second significant digit.
std::string with_error(double value, double error) {
    if (!(error > 0) || !std::isfinite(error)) return significant(value, 6);
    const int decimals = std::clamp(1 - static_cast<int>(std::floor(std::log10(error))), 0, 12);
    char text[80];
    std::snprintf(text, sizeof text, "%.*f ± %.*f", decimals, value, decimals, error);
    return text;
}

// The value's text, or "" when the metadata holds no such value.
std::string value_text(const KeyNumber& entry, const Found& found, const nlohmann::json& meta,
                       std::string& error_path) {
    const nlohmann::json& value = *found.value;
    const std::string kind = entry.kind;
    std::string text;
    if (kind == "count") {
        if (!value.is_array()) return "";
        text = std::to_string(value.size());
    } else if (kind == "range") {
        if (!value.is_array() || value.size() < 2 || !finite_number(&value.front()) || !finite_number(&value.back()))
            return "";
        text = significant(value.front().get<double>(), entry.digits) + " to " +
               significant(value.back().get<double>(), entry.digits);
    } else if (kind == "bounds") {
        if (!value.is_array() || value.size() != 4) return "";
        for (const nlohmann::json& side : value)
            if (!finite_number(&side)) return "";
        text = "x " + significant(value[0].get<double>(), entry.digits) + " to " +
               significant(value[1].get<double>(), entry.digits) + ", y " +
               significant(value[2].get<double>(), entry.digits) + " to " +
               significant(value[3].get<double>(), entry.digits);
    } else if (kind == "integer") {
        if (!value.is_number_integer()) return "";
        text = value.dump();
    } else {
        if (!finite_number(&value)) return "";
        text = significant(value.get<double>(), entry.digits);
        if (*entry.error) {
            const std::string parent = found.pointer.substr(0, found.pointer.rfind('/'));
            const nlohmann::json* error = at_pointer(meta, parent + "/" + entry.error);
            if (finite_number(error)) {
                text = with_error(value.get<double>(), error->get<double>());
                error_path = parent + "/" + entry.error;
            }
        }
    }
    if (*entry.unit) text += std::string(" ") + entry.unit;
    return text;
}

}  // namespace

std::string significant(double value, int digits) {
    if (!std::isfinite(value)) return value != value ? "NaN" : (value > 0 ? "inf" : "-inf");
    digits = std::clamp(digits, 1, 17);
    char text[48];
    // Whole numbers, and numbers too large for their digits, below 10^9 in
    // full: 250000 and 12988, not 2.500e+05 and 1.299e+04.
    if (std::abs(value) < 1e9 && (value == std::floor(value) || std::abs(value) >= std::pow(10.0, digits))) {
        std::snprintf(text, sizeof text, "%.0f", value);
        return text;
    }
    // A number the digits give exactly as it is (0.02 of 100 trials) in
    // its shortest form; a rounded one keeps its trailing zeros (2.000 is
    // not 2).
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) return text;
    std::snprintf(text, sizeof text, "%#.*g", digits, value);
    std::string shown = text;
    if (shown.back() == '.') shown.pop_back();  // "1235." from %#g
    return shown;
}

std::vector<KeyNumberRow> key_numbers(const nlohmann::json& meta) {
    std::vector<KeyNumberRow> rows;
    const nlohmann::json* scene = child(meta, "scene");
    if (!scene || !scene->is_string()) return rows;
    const std::string name = scene->get<std::string>();
    const auto info = std::find_if(scenes::all_scenes().begin(), scenes::all_scenes().end(),
                                   [&](const scenes::SceneInfo& s) { return s.name == name; });
    if (info == scenes::all_scenes().end()) return rows;
    for (const KeyNumber& entry : info->key_numbers) {
        std::vector<Found> found;
        expand(meta, steps_of(entry.path), 0, "", nullptr, 0, found);
        for (const Found& f : found) {
            if (!holds(entry.only, meta, f.element)) continue;
            KeyNumberRow row;
            row.value = value_text(entry, f, meta, row.error_path);
            if (row.value.empty()) continue;
            row.label = label_of(entry.label, f.element, f.index);
            row.path = f.pointer;
            row.kind = entry.kind;
            for (const KeyReference& reference : entry.references)
                if (holds(reference.when, meta, f.element)) {
                    row.reference = reference.text;
                    break;
                }
            rows.push_back(std::move(row));
            if (rows.size() >= 24) return rows;  // a card's table stays short
        }
    }
    return rows;
}

}  // namespace app
