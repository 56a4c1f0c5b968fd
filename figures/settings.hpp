#pragma once
// One section of a figure description ([params], [style], ...) read through
// the list of keys its scene allows. Unknown keys and values of the wrong
// type are errors naming the key and what is allowed; a key that is absent
// keeps the caller's default. Every value read is recorded for the metadata.

#include <toml++/toml.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace figures {

// Thrown for any mistake in a description or a command-line value: the
// command reports it on one line and exits with status 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A UsageError about one key of a description ("params.n"), so the caller
// that knows where the key was written can say so (file and line, or --set).
struct KeyError : UsageError {
    KeyError(std::string full_key, const std::string& message) : UsageError(message), key(std::move(full_key)) {}
    std::string key;  // section.key, e.g. "params.n" or "params.plants[1].axiom"
};

struct Key {
    std::string name;  // as written in the description, e.g. "r"
    std::string help;  // one line: meaning and allowed values
};

// While a SettingsLog lives on a thread, every Settings made there leaves
// its section's allowed keys and the values it read (`figgen describe`).
struct SettingsLog {
    SettingsLog();
    ~SettingsLog();
    SettingsLog(const SettingsLog&) = delete;
    SettingsLog& operator=(const SettingsLog&) = delete;
    struct Section {
        std::string name;
        std::vector<Key> keys;
        nlohmann::json used = nlohmann::json::object();
    };
    std::vector<Section> sections;  // in the order the scene made them; one per name
    Section& section(const std::string& name, const std::vector<Key>& keys);
    SettingsLog* outer;
};

class Settings {
public:
    // Throws UsageError if `table` holds a key not in `allowed`.
    Settings(std::string section, const toml::table& table, std::vector<Key> allowed);
    ~Settings();  // leaves what it read in this thread's SettingsLog, if any
    Settings(const Settings&) = default;

    long long integer(const std::string& key, long long fallback);
    int count(const std::string& key, int fallback);         // an integer that fits an int
    double number(const std::string& key, double fallback);  // accepts integers too
    std::string text(const std::string& key, const std::string& fallback);
    bool flag(const std::string& key, bool fallback);
    std::vector<long long> integers(const std::string& key, const std::vector<long long>& fallback);
    std::vector<double> numbers(const std::string& key, const std::vector<double>& fallback);
    std::vector<std::string> texts(const std::string& key, const std::vector<std::string>& fallback);
    // A list of inline tables ({rule = "0101010", restrict = [1, 16]}, ...),
    // each to be read through a Settings of its own.
    std::vector<toml::table> tables(const std::string& key);
    bool has(const std::string& key) const { return find(key) != nullptr; }

    const std::string& section() const { return section_; }
    const std::vector<Key>& allowed() const { return allowed_; }
    const nlohmann::json& used() const { return used_; }  // every key read, with its effective value

private:
    const toml::node* find(const std::string& key) const;
    [[noreturn]] void wrong_type(const std::string& key, const char* expected) const;

    std::string section_;
    toml::table table_;
    std::vector<Key> allowed_;
    nlohmann::json used_ = nlohmann::json::object();
};

// "a, b, c": the allowed names, for error messages.
std::string key_list(const std::vector<Key>& keys);

}  // namespace figures
