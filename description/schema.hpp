#pragma once
// A section's keys, each declared once: its name, what it holds, its
// default, the range or set it allows, its meaning, and the member it is
// read into. A scene's reading and checking, `figgen describe` and the
// metadata's params/style all come from the declaration.
//
//   const Schema<sim::DiffusionParams> schema = Schema<sim::DiffusionParams>()
//       .count("n", &P::n, "grid size in cells")
//       .choice("boundary", &P::boundary, {{"zero", zero}, {"wrap", wrap}}, "...")
//       .check([](Settings& s, const std::string&, P& p) { check_model(s, [&] { p.validate(); }); });
//
// A range left out of a declaration is the model's (sim's require_*): the
// scene's check runs it, and describe shows it from there.

#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "description/settings.hpp"

namespace description {

template <class T>
class Schema {
public:
    // Reads the key `name` of the section into `value`, refusing what it does not allow.
    using Read = std::function<void(Settings& section, const std::string& name, T& value)>;
    // Reads nothing: a check across keys, after they are all read. `prefix` is
    // the one the schema's keys were given (part()), for naming them.
    using Check = std::function<void(Settings& section, const std::string& prefix, T& value)>;
    // The default as the metadata writes it, from the defaults the section is read over.
    using Fallback = std::function<nlohmann::json(const T& defaults)>;

    // An integer that fits its member; without bounds the model checks it.
    template <class I>
    Schema& count(std::string name, I T::*member, std::string meaning) {
        static_assert(std::is_integral_v<I>);
        return add({std::move(name), std::move(meaning), "an integer"}, member,
                   [member](Settings& s, const std::string& key, T& v) {
                       v.*member = static_cast<I>(s.count(key, static_cast<int>(v.*member)));
                   });
    }
    template <class I>
    Schema& count(std::string name, I T::*member, std::string meaning, int low, int high) {
        return add({std::move(name), std::move(meaning), "an integer", integers_allowed(low, high)}, member,
                   [member, low, high](Settings& s, const std::string& key, T& v) {
                       v.*member = static_cast<I>(s.count_in(key, static_cast<int>(v.*member), low, high));
                   });
    }
    // A number (integers read as numbers) into a double or float member.
    template <class N>
    Schema& number(std::string name, N T::*member, std::string meaning) {
        static_assert(std::is_floating_point_v<N>);
        return add({std::move(name), std::move(meaning), "a number"}, member,
                   [member](Settings& s, const std::string& key, T& v) {
                       v.*member = static_cast<N>(s.number(key, static_cast<double>(v.*member)));
                   });
    }
    template <class N>
    Schema& number(std::string name, N T::*member, std::string meaning, double low, double high) {
        return add({std::move(name), std::move(meaning), "a number", numbers_allowed(low, high)}, member,
                   [member, low, high](Settings& s, const std::string& key, T& v) {
                       v.*member = static_cast<N>(s.number_in(key, static_cast<double>(v.*member), low, high));
                   });
    }
    // A number read only where it is given: absent, the member stays empty
    // and the metadata has no such key.
    Schema& optional_number(std::string name, std::optional<double> T::*member, std::string meaning) {
        return key(
            {std::move(name), std::move(meaning), "a number"},
            [member](Settings& s, const std::string& key, T& v) {
                if (s.has(key)) v.*member = s.number(key, 0.0);
            },
            [member](const T& d) { return d.*member ? nlohmann::json(*(d.*member)) : nlohmann::json(); });
    }
    Schema& text(std::string name, std::string T::*member, std::string meaning) {
        return add({std::move(name), std::move(meaning), "text"}, member,
                   [member](Settings& s, const std::string& key, T& v) { v.*member = s.text(key, v.*member); });
    }
    Schema& flag(std::string name, bool T::*member, std::string meaning) {
        return add({std::move(name), std::move(meaning), "true or false"}, member,
                   [member](Settings& s, const std::string& key, T& v) { v.*member = s.flag(key, v.*member); });
    }
    Schema& numbers(std::string name, std::vector<double> T::*member, std::string meaning) {
        return add({std::move(name), std::move(meaning), "a list of numbers"}, member,
                   [member](Settings& s, const std::string& key, T& v) { v.*member = s.numbers(key, v.*member); });
    }
    Schema& integers(std::string name, std::vector<long long> T::*member, std::string meaning) {
        return add({std::move(name), std::move(meaning), "a list of integers"}, member,
                   [member](Settings& s, const std::string& key, T& v) { v.*member = s.integers(key, v.*member); });
    }
    Schema& texts(std::string name, std::vector<std::string> T::*member, std::string meaning) {
        return add({std::move(name), std::move(meaning), "a list of strings"}, member,
                   [member](Settings& s, const std::string& key, T& v) { v.*member = s.texts(key, v.*member); });
    }
    // A value of any type, read by `read(section, key, fallback)`; the
    // metadata writes it as nlohmann::json does (to_json where it has one).
    template <class M, class R>
    Schema& field(Key declared, M T::*member, R reader) {
        return add(std::move(declared), member, [member, reader](Settings& s, const std::string& key, T& v) {
            v.*member = reader(s, key, static_cast<const M&>(v.*member));
        });
    }
    // One of a set of names, each standing for a value of the member.
    template <class E>
    Schema& choice(std::string name, E T::*member, std::vector<std::pair<std::string, E>> names, std::string meaning) {
        std::vector<std::string> words;
        for (const auto& n : names) words.push_back(n.first);
        const std::string allowed = names_allowed(words);
        auto word = [names](const E& value) {
            for (const auto& n : names)
                if (n.second == value) return n.first;
            return std::string();
        };
        return key(
            {std::move(name), std::move(meaning), "text", allowed},
            [member, names, word, allowed](Settings& s, const std::string& key, T& v) {
                const std::string given = s.text(key, word(v.*member));
                for (const auto& n : names)
                    if (n.first == given) {
                        v.*member = n.second;
                        return;
                    }
                s.refuse(key, allowed);
            },
            [member, word](const T& d) { return nlohmann::json(word(d.*member)); });
    }
    // A key read its own way (a list of colours, a value another key bounds);
    // `fallback` gives its default where it has one of its own.
    Schema& key(Key declared, Read reader, Fallback fallback = {}) {
        fields_.push_back({std::move(declared), std::move(reader), std::move(fallback)});
        return *this;
    }
    Schema& check(Check check) {
        checks_.push_back(std::move(check));
        return *this;
    }
    // `other`'s keys, their names after `prefix`, read into `member`.
    template <class U>
    Schema& part(const Schema<U>& other, U T::*member, const std::string& prefix = "") {
        return part_at(
            other, [member](auto& value) -> auto& { return value.*member; }, prefix);
    }
    // The same into what `at(value)` gives: a generic lambda taking T& or
    // const T& and giving the U in it (an element of a list, say).
    template <class U, class At>
    Schema& part_at(const Schema<U>& other, At at, const std::string& prefix = "") {
        for (const auto& f : other.fields()) {
            Key k = f.key;
            k.name = prefix + k.name;
            key(
                std::move(k),
                [at, reader = f.read](Settings& s, const std::string& name, T& v) { reader(s, name, at(v)); },
                f.fallback ? Fallback([at, fb = f.fallback](const T& d) { return fb(at(d)); }) : Fallback());
        }
        for (const auto& c : other.checks())
            check([at, c, prefix](Settings& s, const std::string& outer, T& v) { c(s, outer + prefix, at(v)); });
        return *this;
    }

    // The section's keys, with their defaults taken from `defaults`.
    std::vector<Key> keys(const T& defaults = T{}) const {
        std::vector<Key> keys;
        for (const auto& f : fields_) {
            keys.push_back(f.key);
            if (f.fallback) keys.back().fallback = f.fallback(defaults);
        }
        return keys;
    }
    // Reads every key over `value`'s defaults, then runs the checks.
    T read(Settings& section, T value = T{}) const {
        for (const auto& f : fields_) f.read(section, f.key.name, value);
        for (const auto& c : checks_) c(section, "", value);
        return value;
    }

    // Reads each key from the section `section_of(key)` gives, for keys that
    // either of two sections may give (a plant's own table, or the figure's
    // [params] for every plant). The checks are the caller's.
    T read_each(const std::function<Settings&(const std::string& key)>& section_of, T value = T{}) const {
        for (const auto& f : fields_) f.read(section_of(f.key.name), f.key.name, value);
        return value;
    }

    struct Field {
        Key key;
        Read read;
        Fallback fallback;
    };
    const std::vector<Field>& fields() const { return fields_; }
    const std::vector<Check>& checks() const { return checks_; }

private:
    template <class M>
    Schema& add(Key declared, M T::*member, Read reader) {
        return key(std::move(declared), std::move(reader), [member](const T& d) { return nlohmann::json(d.*member); });
    }

    std::vector<Field> fields_;
    std::vector<Check> checks_;
};

}  // namespace description
