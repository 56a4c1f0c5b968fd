#include "description/settings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "description/plain_name.hpp"

namespace description {

SettingError::SettingError(std::string key, std::string value, std::string allowed)
    : SettingError(key, value, allowed,
                   // A key may be any text a file quoted: shown escaped, on one line.
                   value.empty() ? printable_short(as_written(key), 100) + " is missing: give " + allowed
                                 : printable_short(as_written(key), 100) + " = " + value + " is not allowed: " + allowed) {}

SettingError::SettingError(std::string key, std::string value, std::string allowed, const std::string& message)
    : UsageError(message), key_(std::move(key)), value_(std::move(value)), allowed_(std::move(allowed)) {}

SettingError SettingError::at(const std::string& where) const {
    SettingError located(key_, value_, allowed_, where + ": " + what());
    located.where_ = where;
    return located;
}

SettingError SettingError::unknown(std::string key, const std::string& allowed_keys) {
    const std::string message = "unknown key " + printable_short(key, 100) + "; allowed: " + allowed_keys;
    return SettingError(std::move(key), "", allowed_keys, message);
}

std::string as_written(const std::string& key) {
    for (const std::string bare : {"params.", "description."})
        if (key.rfind(bare, 0) == 0) return key.substr(bare.size());
    return key;
}

std::string shown(double value) {
    std::ostringstream text;
    text << value;  // the stream's default: %g, 6 significant digits
    return text.str();
}

std::string key_list(const std::vector<Key>& keys) {
    std::string list;
    for (const Key& k : keys) list += (list.empty() ? "" : ", ") + k.name;
    return list.empty() ? "(none)" : list;
}

namespace {
thread_local SettingsLog* current_settings_log = nullptr;
}  // namespace

SettingsLog::SettingsLog() : outer(current_settings_log) { current_settings_log = this; }
SettingsLog::~SettingsLog() { current_settings_log = outer; }

SettingsLog::Section& SettingsLog::section(const std::string& name, const std::vector<Key>& keys) {
    for (Section& s : sections)
        if (s.name == name) return s;
    sections.push_back({name, keys, nlohmann::json::object(), {}});
    return sections.back();
}

Settings::~Settings() {
    if (!current_settings_log) return;
    SettingsLog::Section& logged = current_settings_log->section(section_, allowed_);
    for (const auto& [key, value] : used_.items())
        if (!logged.used.contains(key)) logged.used[key] = value;
}

Settings::Settings(std::string section, const toml::table& table, std::vector<Key> allowed)
    : section_(std::move(section)), table_(table), allowed_(std::move(allowed)) {
    if (current_settings_log) current_settings_log->section(section_, allowed_);
    for (const auto& entry : table_) {
        const toml::key& key = entry.first;  // not a structured binding: clang 14 cannot capture those
        const bool known =
            std::any_of(allowed_.begin(), allowed_.end(), [&](const Key& k) { return k.name == key.str(); });
        if (!known)
            throw SettingError::unknown(section_ + "." + std::string(key.str()), key_list(allowed_));
    }
}

const toml::node* Settings::find(const std::string& key) const {
    const bool known = std::any_of(allowed_.begin(), allowed_.end(), [&](const Key& k) { return k.name == key; });
    if (!known) throw std::logic_error("scene reads undeclared key " + section_ + "." + key);
    return table_.get(key);
}

void Settings::wrong_type(const std::string& key, const char* expected) {
    refuse(key, std::string("expected ") + expected);
}

void Settings::refuse(const std::string& key, const std::string& value, const std::string& allowed) {
    throw SettingError(section_ + "." + key, value, allowed);
}

void Settings::refuse(const std::string& key, const std::string& allowed) {
    std::string value;
    if (const toml::node* node = table_.get(key)) {
        if (const auto* number = node->as_floating_point()) {
            value = shown(number->get());  // 1e+308, not 309 digits
        } else {
            std::ostringstream text;
            node->visit([&](const auto& n) { text << n; });
            value = text.str();
        }
    } else if (used_.contains(key)) {
        value = used_[key].is_number_float() ? shown(used_[key].get<double>()) : used_[key].dump();
    }
    // One line: toml++ prints a long array across several.
    std::string line;
    for (char c : value)
        if (c == '\n' || c == '\t' || c == ' ') {
            if (!line.empty() && line.back() != ' ') line += ' ';
        } else {
            line += c;
        }
    if (line.size() > 60) line = line.substr(0, 57) + "...";
    refuse(key, line, allowed);
}

const std::string& Settings::checked_text(const std::string& key, const std::string& value) {
    if (!is_text(value)) refuse(key, "\"" + printable_short(value) + "\"", text_allowed);
    return value;
}

void Settings::note_allowed(const std::string& key, const std::string& allowed) {
    if (current_settings_log) current_settings_log->section(section_, allowed_).allowed[key] = allowed;
}

std::string integers_allowed(long long low, long long high) {
    return "an integer from " + std::to_string(low) + " to " + std::to_string(high);
}

std::string numbers_allowed(double low, double high) {
    return "a number from " + shown(low) + " to " + shown(high);
}

std::string names_allowed(const std::vector<std::string>& names) {
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i) {
        list += i == 0 ? "" : i + 1 == names.size() ? " or " : ", ";
        list += '"';  // appended in steps: GCC 12 warns falsely (-Wrestrict) on "\"" + std::string
        list += names[i];
        list += '"';
    }
    return list;
}

int Settings::count_in(const std::string& key, int fallback, int low, int high) {
    const std::string allowed = integers_allowed(low, high);
    note_allowed(key, allowed);
    const long long value = integer(key, fallback);
    if (value < low || value > high) refuse(key, std::to_string(value), allowed);
    return static_cast<int>(value);
}

double Settings::number_in(const std::string& key, double fallback, double low, double high) {
    const std::string allowed = numbers_allowed(low, high);
    note_allowed(key, allowed);
    const double value = number(key, fallback);
    if (!(value >= low && value <= high)) refuse(key, shown(value), allowed);
    return value;
}

long long Settings::integer(const std::string& key, long long fallback) {
    long long value = fallback;
    if (const toml::node* node = find(key)) {
        if (!node->is_integer()) wrong_type(key, "an integer");
        value = node->as_integer()->get();
    }
    used_[key] = value;
    return value;
}

int Settings::count(const std::string& key, int fallback) {
    const long long value = integer(key, fallback);
    if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max())
        wrong_type(key, "an integer of at most 10 digits");
    return static_cast<int>(value);
}

double Settings::number(const std::string& key, double fallback) {
    double value = fallback;
    if (const toml::node* node = find(key)) {
        if (node->is_integer())
            value = static_cast<double>(node->as_integer()->get());
        else if (node->is_floating_point())
            value = node->as_floating_point()->get();
        else
            wrong_type(key, "a number");
        // TOML admits nan and inf; no figure parameter does.
        if (!std::isfinite(value)) wrong_type(key, "a finite number");
    }
    used_[key] = value;
    return value;
}

std::string Settings::text(const std::string& key, const std::string& fallback) {
    std::string value = fallback;
    if (const toml::node* node = find(key)) {
        // A digit string given on the command line (--set rule=1100000) reads
        // as a TOML integer; its digits are the text meant.
        if (node->is_integer())
            value = std::to_string(node->as_integer()->get());
        else if (!node->is_string())
            wrong_type(key, "a string");
        else
            value = checked_text(key, node->as_string()->get());
    }
    used_[key] = value;
    return value;
}

bool Settings::flag(const std::string& key, bool fallback) {
    bool value = fallback;
    if (const toml::node* node = find(key)) {
        if (!node->is_boolean()) wrong_type(key, "true or false");
        value = node->as_boolean()->get();
    }
    used_[key] = value;
    return value;
}

std::vector<long long> Settings::integers(const std::string& key, const std::vector<long long>& fallback) {
    std::vector<long long> values = fallback;
    if (const toml::node* node = find(key)) {
        const toml::array* array = node->as_array();
        if (!array) wrong_type(key, "a list of integers");
        values.clear();
        for (const toml::node& item : *array) {
            if (!item.is_integer()) wrong_type(key, "a list of integers");
            values.push_back(item.as_integer()->get());
        }
    }
    used_[key] = values;
    return values;
}

std::vector<double> Settings::numbers(const std::string& key, const std::vector<double>& fallback) {
    std::vector<double> values = fallback;
    if (const toml::node* node = find(key)) {
        const toml::array* array = node->as_array();
        if (!array) wrong_type(key, "a list of numbers");
        values.clear();
        for (const toml::node& item : *array) {
            if (item.is_integer())
                values.push_back(static_cast<double>(item.as_integer()->get()));
            else if (item.is_floating_point() && std::isfinite(item.as_floating_point()->get()))
                values.push_back(item.as_floating_point()->get());
            else
                wrong_type(key, "a list of finite numbers");
        }
    }
    used_[key] = values;
    return values;
}

std::vector<std::string> Settings::texts(const std::string& key, const std::vector<std::string>& fallback) {
    std::vector<std::string> values = fallback;
    if (const toml::node* node = find(key)) {
        const toml::array* array = node->as_array();
        if (!array) wrong_type(key, "a list of strings");
        values.clear();
        for (const toml::node& item : *array) {
            if (!item.is_string()) wrong_type(key, "a list of strings");
            values.push_back(checked_text(key, item.as_string()->get()));
        }
    }
    used_[key] = values;
    return values;
}

std::vector<toml::table> Settings::tables(const std::string& key) {
    std::vector<toml::table> values;
    if (const toml::node* node = find(key)) {
        const toml::array* array = node->as_array();
        if (!array) wrong_type(key, "a list of tables, e.g. [{rule = \"0101010\"}]");
        for (const toml::node& item : *array) {
            if (!item.is_table()) wrong_type(key, "a list of tables, e.g. [{rule = \"0101010\"}]");
            values.push_back(*item.as_table());
        }
    }
    return values;  // each table's values are recorded by the Settings that reads it
}

}  // namespace description
