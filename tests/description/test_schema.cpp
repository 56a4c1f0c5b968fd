// A section's schema: each key declared once gives the keys a section
// allows, their defaults and what they allow, and reads them into members.
#include <catch2/catch.hpp>

#include "description/schema.hpp"

using description::Schema;
using description::SettingError;
using description::Settings;

namespace {

enum class Edge { zero, wrap };

struct Look {
    double alpha = 0.7;
    std::optional<double> vmin;
};

struct Params {
    int n = 64;
    double r = 0.25;
    Edge edge = Edge::zero;
    bool smooth = false;
    std::vector<double> range{0.1, 0.2};
    Look a, b;
};

Schema<Look> look_schema() {
    return Schema<Look>()
        .number("alpha", &Look::alpha, "opacity", 0.0, 1.0)
        .optional_number("vmin", &Look::vmin, "lowest value")
        .check([](Settings& s, const std::string& prefix, Look& look) {
            if (look.vmin && *look.vmin > 10) s.refuse(prefix + "vmin", "at most 10");
        });
}

Schema<Params> params_schema() {
    return Schema<Params>()
        .count("n", &Params::n, "cells a side", 1, 100)
        .number("r", &Params::r, "rate")
        .choice("edge", &Params::edge, {{"zero", Edge::zero}, {"wrap", Edge::wrap}}, "beyond the edge")
        .flag("smooth", &Params::smooth, "smoothed")
        .numbers("range", &Params::range, "[low, high]")
        .part(look_schema(), &Params::a, "a_")
        .part(look_schema(), &Params::b, "b_")
        .check([](Settings& s, const std::string&, Params& p) {
            if (p.r > 1) s.refuse("r", "a rate of at most 1");
        });
}

toml::table parsed(const char* text) {
    return toml::parse(text);
}

}  // namespace

TEST_CASE("a schema lists each key once, with its type, default and what it allows", "[schema]") {
    Params defaults;
    defaults.n = 32;  // a scene's own default, over the struct's
    const auto keys = params_schema().keys(defaults);
    std::vector<std::string> names;
    for (const auto& k : keys) names.push_back(k.name);
    CHECK(names ==
          std::vector<std::string>{"n", "r", "edge", "smooth", "range", "a_alpha", "a_vmin", "b_alpha", "b_vmin"});
    CHECK(keys[0].type == "an integer");
    CHECK(keys[0].allowed == "an integer from 1 to 100");
    CHECK(keys[0].fallback == 32);
    CHECK(keys[1].allowed.empty());  // the model's to check
    CHECK(keys[2].allowed == "\"zero\" or \"wrap\"");
    CHECK(keys[2].fallback == "zero");
    CHECK(keys[4].fallback == nlohmann::json({0.1, 0.2}));
    CHECK(keys[5].allowed == "a number from 0 to 1");
    CHECK(keys[6].fallback.is_null());  // no value unless given
}

TEST_CASE("a schema reads every key into its member over the defaults, and records it", "[schema]") {
    const auto schema = params_schema();
    Settings s("params", parsed("n = 7\nedge = \"wrap\"\nb_alpha = 0.5\nb_vmin = -1"), schema.keys());
    const Params p = schema.read(s);
    CHECK(p.n == 7);
    CHECK(p.r == 0.25);
    CHECK(p.edge == Edge::wrap);
    CHECK(p.a.alpha == 0.7);
    CHECK(!p.a.vmin);
    CHECK(p.b.alpha == 0.5);
    CHECK(p.b.vmin == -1.0);
    CHECK(s.used()["edge"] == "wrap");
    CHECK(s.used()["r"] == 0.25);
    CHECK(!s.used().contains("a_vmin"));  // read only where given
}

TEST_CASE("a schema refuses what a key does not allow, naming the key as written", "[schema]") {
    const auto schema = params_schema();
    auto refusal = [&](const char* text) {
        Settings s("params", parsed(text), schema.keys());
        try {
            schema.read(s);
        } catch (const SettingError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(refusal("n = 0") == "n = 0 is not allowed: an integer from 1 to 100");
    CHECK(refusal("edge = \"torus\"") == "edge = 'torus' is not allowed: \"zero\" or \"wrap\"");
    CHECK(refusal("smooth = 1") == "smooth = 1 is not allowed: expected true or false");
    CHECK(refusal("r = 2") == "r = 2 is not allowed: a rate of at most 1");
    CHECK(refusal("b_vmin = 11") == "b_vmin = 11 is not allowed: at most 10");  // a part's check, with its prefix
    CHECK(refusal("a_alpha = 1.5") == "a_alpha = 1.5 is not allowed: a number from 0 to 1");
    CHECK_THROWS_WITH(Settings("params", parsed("colour = 1"), schema.keys()),
                      Catch::StartsWith("unknown key params.colour; allowed: n, r, edge"));
}
