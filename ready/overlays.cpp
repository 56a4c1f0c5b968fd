// The start's overlays of a Ready pattern (<initial_pattern_generator>) as params.initial.
#include "ready/reading.hpp"

#include <algorithm>
#include <iterator>

#include "description/plain_name.hpp"

namespace ready::reading {

using description::printable_short;

namespace {

toml::array point(const XMLElement* p) {
    return toml::array{as_float(attribute(p, "x")), as_float(attribute(p, "y")), as_float(attribute(p, "z"))};
}

// The nested point elements (point3D, any case) in order.
std::vector<const XMLElement*> points(const XMLElement* e, std::size_t count) {
    std::vector<const XMLElement*> out;
    for (const XMLElement* c = e->FirstChildElement(); c && out.size() <= count; c = c->NextSiblingElement())
        out.push_back(c);
    if (out.size() != count)
        throw Refused(element(e) + " needs " + std::to_string(count) + " nested point3D elements");
    return out;
}

// A fill's numbers (Ready's attribute, figgen's key, Ready's default if it
// has one) and its nested points, in order.
struct Number {
    const char* attribute;
    const char* key;
    std::optional<double> fallback;
};
struct FillKeys {
    const char* fill;
    std::vector<Number> numbers;
    std::vector<const char*> points;
};
const FillKeys fill_keys[] = {
    {"constant", {{"value", "value", {}}}, {}},
    {"white_noise", {{"low", "low", {}}, {"high", "high", {}}}, {}},
    {"perlin_noise", {{"scale", "scale", 64}}, {}},
    {"linear_gradient", {{"val1", "val1", {}}, {"val2", "val2", {}}}, {"from", "to"}},
    {"radial_gradient", {{"val1", "val1", {}}, {"val2", "val2", {}}}, {"from", "to"}},
    {"gaussian", {{"height", "height", {}}, {"sigma", "sigma", {}}}, {"centre"}},
    {"sine", {{"phase", "phase", {}}, {"amplitude", "amplitude", {}}}, {"from", "to"}},
    {"other_chemical", {}, {}},
    {"parameter", {}, {}},
};


void read_fill(const XMLElement* e, int chemicals, toml::table& t, std::set<std::string>& parameters_used) {
    const std::string name = e->Name();
    t.insert_or_assign("fill", name);
    for (const FillKeys& f : fill_keys) {
        if (name != f.fill) continue;
        for (const Number& n : f.numbers) t.insert(n.key, as_float(attribute(e, n.attribute, n.fallback)));
        if (!f.points.empty()) {
            const auto p = points(e, f.points.size());
            for (std::size_t k = 0; k < p.size(); ++k) t.insert(f.points[k], point(p[k]));
        }
    }
    if (name == "perlin_noise") t.insert("octaves", integer(e, "num_octaves", 8, 1, 16));
    if (name == "other_chemical") {
        const std::string other = text_attribute(e, "chemical", "");
        if (!is_chemical(other, chemicals))
            throw Refused("an overlay's <other_chemical chemical> is \"" + printable_short(other) +
                          "\", not one of the rule's");
        t.insert("other", other);
    } else if (name == "parameter") {
        const std::string p = text_attribute(e, "name", "");
        if (!description::is_text(p)) throw Refused("an overlay's <parameter name> is not " + std::string(description::text_allowed));
        t.insert("parameter", p);  // data: the scene checks it names one of the rule's parameters
        parameters_used.insert(p);
    }
}

// One shape of an overlay, or nothing when it can never apply.
std::optional<toml::table> read_shape(const XMLElement* e) {
    const std::string name = e->Name();
    toml::table s{{"shape", name}};
    if (name == "rectangle") {
        const auto p = points(e, 2);
        s.insert("from", point(p[0]));
        s.insert("to", point(p[1]));
    } else if (name == "circle") {
        s.insert("radius", as_float(attribute(e, "radius")));
        s.insert("centre", point(points(e, 1)[0]));
    } else if (name == "pixel") {
        // Ready compares the cell's coordinates along the grid's axes alone
        // (z is ignored on a 2-D grid, y and z on a 1-D one).
        const double x = attribute(e, "x"), y = attribute(e, "y"), z = attribute(e, "z", 0);
        if (x < 0 || y < 0 || z < 0 || x > 1e5 || y > 1e5 || z > 1e5) return std::nullopt;  // never a cell
        toml::array at{static_cast<std::int64_t>(x), static_cast<std::int64_t>(y)};
        if (z != 0) at.push_back(static_cast<std::int64_t>(z));
        s.insert("at", std::move(at));
    }
    return s;
}

// One <overlay> as a table of params.initial, or nothing when it can never apply.
}  // namespace

std::optional<toml::table> overlay(const XMLElement* o, int chemicals, std::set<std::string>& parameters_used) {
    toml::table t;
    const std::string chemical = text_attribute(o, "chemical", "");
    if (!is_chemical(chemical, chemicals))
        throw Refused("an <overlay chemical> is \"" + printable_short(chemical) + "\", not one of the rule's");
    t.insert("chemical", chemical);
    static const std::set<std::string> operations = {"overwrite", "add", "subtract", "multiply", "divide"};
    static const std::set<std::string> shape_names = {"everywhere", "rectangle", "circle", "pixel"};
    toml::array shapes;
    bool has_operation = false, has_fill = false, any_shape = false;
    for (const XMLElement* e = o->FirstChildElement(); e; e = e->NextSiblingElement()) {
        const std::string name = e->Name();
        const bool fill = std::any_of(std::begin(fill_keys), std::end(fill_keys),
                                      [&](const FillKeys& f) { return name == f.fill; });
        if (operations.count(name)) {
            t.insert_or_assign("operation", name);
            has_operation = true;
        } else if (fill) {
            read_fill(e, chemicals, t, parameters_used);
            has_fill = true;
        } else if (shape_names.count(name)) {
            any_shape = true;
            if (auto s = read_shape(e)) shapes.push_back(std::move(*s));
        } else {
            throw Refused("an <overlay> holds " + element(e) + ", which Ready's overlays do not know");
        }
    }
    if (!has_operation || !has_fill || !any_shape)
        throw Refused("an <overlay> needs an operation, a fill and a shape, as Ready's do");
    if (shapes.empty()) return std::nullopt;
    t.insert("shapes", std::move(shapes));
    return t;
}

}  // namespace ready::reading
