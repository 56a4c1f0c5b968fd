#pragma once
// One section of a figure description ([params], [style], ...) read through
// the list of keys its scene allows. Unknown keys and values of the wrong
// type are errors naming the key and what is allowed; a key that is absent
// keeps the caller's default. Every value read is recorded for the metadata.

#include <toml++/toml.h>

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace description {

// Thrown for any mistake on the command line or in a description: the
// command reports it on one line and exits with status 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A file given as the figure that figgen cannot read as one: a Ready
// pattern that is damaged, not a pattern, or of a kind figgen does not run
// yet. A UsageError too (exit 2); Python raises it as figgen.FileError.
struct FileError : UsageError {
    using UsageError::UsageError;
};

// A setting that is not allowed: the one error every description key, scene
// setting and model parameter check raises. It carries the key as the
// description names it ("params.n", "params.plants[1].angle", "style.sides");
// the one place that catches it (at_source in description.hpp) adds where
// that key was written: file and line, or the --set that gave it.
class SettingError : public UsageError {
public:
    // "n = -3 is not allowed: an integer from 1 to 8192"; with no value,
    // a key that must be given: "scene is missing: give a scene name, ..."
    SettingError(std::string key, std::string value, std::string allowed);
    // An unknown key: "unknown key style.colour; allowed: a, b, c"
    static SettingError unknown(std::string key, const std::string& allowed_keys);

    const std::string& key() const { return key_; }
    const std::string& value() const { return value_; }
    const std::string& allowed() const { return allowed_; }
    // Where the key was given ("tc7-1.toml:15", "--set r=0.5"); empty until
    // at_source (description.hpp) says.
    const std::string& where() const { return where_; }
    // The same error, its message beginning with where the key was given.
    SettingError at(const std::string& where) const;

private:
    SettingError(std::string key, std::string value, std::string allowed, const std::string& message);
    std::string key_, value_, allowed_, where_;
};

// A key as a user writes it with --set: [params] and top-level keys bare
// ("n", "plants[1].angle", "seed"), others with their section ("style.sides").
std::string as_written(const std::string& key);

// A number as messages show it, at most 6 significant digits: "1e+308", "0.25".
std::string shown(double value);

// One key of a section, as its schema (description/schema.hpp) declares it.
struct Key {
    std::string name;           // as written in the description, e.g. "r"
    std::string help;           // its meaning, one line
    std::string type{};         // what it holds: "an integer", "a number", "text", ...
    std::string allowed{};      // the range or set the declaration states; empty: the model checks it
    nlohmann::json fallback{};  // its default; null where none, or where other keys decide it
};

// What a ranged read allows: "an integer from 1 to 64", "a number from 0 to 1".
std::string integers_allowed(long long low, long long high);
std::string numbers_allowed(double low, double high);
// A set of names: "\"a\", \"b\" or \"c\"".
std::string names_allowed(const std::vector<std::string>& names);

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
        std::map<std::string, std::string> allowed;  // key -> what a ranged read allows
    };
    std::vector<Section> sections;  // in the order the scene made them; one per name
    Section& section(const std::string& name, const std::vector<Key>& keys);
    SettingsLog* outer;
};

class Settings {
public:
    // Throws SettingError if `table` holds a key not in `allowed`.
    Settings(std::string section, const toml::table& table, std::vector<Key> allowed);
    ~Settings();  // leaves what it read in this thread's SettingsLog, if any
    Settings(const Settings&) = default;

    long long integer(const std::string& key, long long fallback);
    int count(const std::string& key, int fallback);         // an integer that fits an int
    double number(const std::string& key, double fallback);  // accepts integers too
    // A string, refused unless it is valid UTF-8 text (is_text in plain_name.hpp).
    std::string text(const std::string& key, const std::string& fallback);
    bool flag(const std::string& key, bool fallback);
    // The same, refused (SettingError) outside [low, high].
    int count_in(const std::string& key, int fallback, int low, int high);
    double number_in(const std::string& key, double fallback, double low, double high);
    std::vector<long long> integers(const std::string& key, const std::vector<long long>& fallback);
    std::vector<double> numbers(const std::string& key, const std::vector<double>& fallback);
    std::vector<std::string> texts(const std::string& key, const std::vector<std::string>& fallback);
    // A list of inline tables ({rule = "0101010", restrict = [1, 16]}, ...),
    // each to be read through a Settings of its own.
    std::vector<toml::table> tables(const std::string& key);
    bool has(const std::string& key) const { return find(key) != nullptr; }
    // The value as written, for a key read its own way (nested lists); null when absent.
    const toml::node* node(const std::string& key) const { return find(key); }

    const std::string& section() const { return section_; }
    const std::vector<Key>& allowed() const { return allowed_; }
    const nlohmann::json& used() const { return used_; }  // every key read, with its effective value

    // Throws the SettingError of this section's `key`: `value` as shown, and
    // what is allowed. Not const: a scene refuses a setting while it reads
    // them (phase 1), never from its const render().
    [[noreturn]] void refuse(const std::string& key, const std::string& value, const std::string& allowed);
    // The same with the value as read (numbers short, strings quoted).
    [[noreturn]] void refuse(const std::string& key, const std::string& allowed);

private:
    const toml::node* find(const std::string& key) const;
    [[noreturn]] void wrong_type(const std::string& key, const char* expected);
    void note_allowed(const std::string& key, const std::string& allowed);
    // `value`, a string `key` holds, refused unless it is text (is_text in
    // plain_name.hpp): every string may be drawn, so the line breaker and
    // the shaper get only characters, and before any model runs.
    const std::string& checked_text(const std::string& key, const std::string& value);

    std::string section_;
    toml::table table_;
    std::vector<Key> allowed_;
    nlohmann::json used_ = nlohmann::json::object();
};

// "a, b, c": the allowed names, for error messages.
std::string key_list(const std::vector<Key>& keys);

}  // namespace description
