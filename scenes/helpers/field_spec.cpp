#include "scenes/helpers/field_spec.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace scenes {

namespace {

glm::vec3 to_hsv(glm::vec3 c) {
    const float hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b}), range = hi - lo;
    float h = 0;
    if (range > 0) {
        if (hi == c.r) h = (c.g - c.b) / range;
        else if (hi == c.g) h = 2 + (c.b - c.r) / range;
        else h = 4 + (c.r - c.g) / range;
        h /= 6;
        if (h < 0) h += 1;
    }
    return {h, hi > 0 ? range / hi : 0.0f, hi};
}

glm::vec3 from_hsv(glm::vec3 hsv) {
    const float h = hsv.x * 6, s = hsv.y, v = hsv.z;
    const int sector = static_cast<int>(std::floor(h)) % 6;
    const float f = h - std::floor(h), p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    switch (sector) {
        case 0: return {v, t, p};
        case 1: return {q, v, p};
        case 2: return {p, v, t};
        case 3: return {p, q, v};
        case 4: return {t, p, v};
        default: return {v, p, q};
    }
}

// 256 colours through the stops, evenly spaced, blended in RGB or (hue
// not wrapping round, as VTK's HSVWrapOff) in HSV.
std::vector<glm::vec3> ramp(const std::vector<glm::vec3>& stops, bool hsv) {
    if (stops.size() < 2) return stops;
    std::vector<glm::vec3> out(256);
    for (int i = 0; i < 256; ++i) {
        const float t = static_cast<float>(i) / 255.0f * static_cast<float>(stops.size() - 1);
        const std::size_t k = std::min(stops.size() - 2, static_cast<std::size_t>(t));
        const float f = t - static_cast<float>(k);
        out[static_cast<std::size_t>(i)] = hsv ? from_hsv(glm::mix(to_hsv(stops[k]), to_hsv(stops[k + 1]), f))
                                               : glm::mix(stops[k], stops[k + 1], f);
    }
    return out;
}

// The key beside `key` in its part: "b_colours" for ("b_blend", "blend", "colours").
std::string sibling(const std::string& key, const std::string& own, const std::string& other) {
    return key.substr(0, key.size() - own.size()) + other;
}

render::Colormap listed_colours(Settings& style, const std::string& key) {
    std::vector<glm::vec3> colours;
    for (const std::string& c : style.texts(key, {})) {
        const auto colour = render::find_colour(c);
        if (!colour) style.refuse(key, "\"" + c + "\"", "colours, each " + render::colours_allowed());
        colours.push_back(*colour);
    }
    if (colours.empty() || colours.size() > 4096) style.refuse(key, "1 to 4096 colours");
    return render::listed_colormap("listed", colours);
}

// Read in this order: colours make a listed map, blend turns its colours into
// a ramp's stops, and colormap (read whenever given, so that a bad name is
// refused beside colours too) names a map where no colours are listed.
description::Schema<FieldSpec> make_field_spec_schema() {
    description::Schema<FieldSpec> schema;
    schema.key({"colours", "a list of colours for the states 0, 1, ... (#rrggbb or names), instead of colormap",
                "a list of colours"},
               [](Settings& style, const std::string& key, FieldSpec& spec) {
                   if (style.has(key)) spec.colormap = listed_colours(style, key);
               });
    schema.key({"blend",
                "\"none\": one colour of colours a state; \"rgb\" or \"hsv\": colours are stops of a smooth ramp, "
                "blended in RGB or HSV (Ready's \"HSV blend\")",
                "text", description::names_allowed({"none", "rgb", "hsv"}), "none"},
               [](Settings& style, const std::string& key, FieldSpec& spec) {
                   if (!style.has(key)) return;  // read only when given: figures without it keep their metadata
                   const std::string colours = sibling(key, "blend", "colours");
                   if (!style.has(colours)) style.refuse(key, "only beside " + colours + ", the stops it blends");
                   const std::string blend = style.text(key, "none");
                   if (blend != "none" && blend != "rgb" && blend != "hsv")
                       style.refuse(key, description::names_allowed({"none", "rgb", "hsv"}));
                   if (blend != "none")
                       spec.colormap = render::listed_colormap("listed", ramp(spec.colormap.colours, blend == "hsv"));
               });
    std::string maps;
    for (const auto& n : render::colormap_names()) maps += (maps.empty() ? "" : ", ") + n;
    const std::string maps_allowed = "one of " + maps;
    schema.key(
        {"colormap", "the field's colormap (--cmap sets it)", "text", maps_allowed},
        [maps_allowed](Settings& style, const std::string& key, FieldSpec& spec) {
            const bool listed = style.has(sibling(key, "colormap", "colours"));
            if (listed && !style.has(key)) return;
            const std::string name = style.text(key, spec.colormap.name);
            const render::Colormap* map = render::find_colormap(name);
            if (!map && name != spec.colormap.name)  // not a scene's own listed map either
                style.refuse(key, maps_allowed);
            // One of the two: a colormap given beside colours would be ignored in silence.
            if (listed)
                style.refuse(key, "no colormap where " + sibling(key, "colormap", "colours") +
                                      " gives the colours: give one of the two (--cmap replaces colours)");
            if (map) spec.colormap = *map;
        },
        [](const FieldSpec& d) { return nlohmann::json(d.colormap.name); });
    schema.optional_number("vmin", &FieldSpec::vmin, "value of the first colour; absent: the panel's minimum");
    schema.optional_number("vmax", &FieldSpec::vmax, "value of the last colour; absent: the panel's maximum");
    schema.check([](Settings& style, const std::string& prefix, FieldSpec& spec) {
        if (spec.vmin && spec.vmax && !(*spec.vmax > *spec.vmin))
            style.refuse(prefix + "vmax",
                         "a number greater than " + prefix + "vmin = " + description::shown(*spec.vmin));
    });
    schema.number("alpha", &FieldSpec::alpha, "opacity over what lies below", 0.0, 1.0);
    schema.choice("sampling", &FieldSpec::sampling,
                  {{"nearest", render::Sampling::nearest}, {"smooth", render::Sampling::smooth}},
                  "cells drawn as squares, or smoothed between their centres");
    schema.flag("colour_bar", &FieldSpec::colour_bar, "a colour bar with ticks beside each panel");
    schema.text("colour_bar_label", &FieldSpec::colour_bar_label, "the colour bar's label");
    return schema;
}

}  // namespace

const description::Schema<FieldSpec>& field_spec_schema() {
    static const description::Schema<FieldSpec> schema = make_field_spec_schema();
    return schema;
}

namespace {

FieldLayer layer_over(LayerCells cells, int rows, int cols, const FieldSpec& spec) {
    FieldLayer layer{rows, cols, std::move(cells), {}};
    double vmin = 0, vmax = 0;
    if (!spec.vmin || !spec.vmax) {  // autoscale: a pass over the cells only when a bound is missing
        const auto [lo, hi] = std::minmax_element(layer.values.begin(), layer.values.end());
        vmin = *lo;
        vmax = *hi;
    }
    vmin = spec.vmin.value_or(vmin);
    vmax = spec.vmax.value_or(vmax);
    // matplotlib maps everything to the first colour when the range is empty.
    if (!(vmax > vmin)) vmax = vmin + 1;
    layer.style = {&spec.colormap, vmin, vmax, spec.alpha, spec.sampling};
    if (spec.colour_bar) layer.colour_bar = render::ColourBar{spec.colormap, vmin, vmax, spec.colour_bar_label};
    return layer;
}

}  // namespace

FieldLayer field_layer(const sim::Grid<double>& values, const FieldSpec& spec, Cells cells) {
    return layer_over(cells == Cells::viewed ? LayerCells::view(values.cells()) : LayerCells(values.cells()),
                      values.rows(), values.cols(), spec);
}

FieldLayer field_layer(const sim::Grid<std::uint8_t>& values, const FieldSpec& spec) {
    std::vector<double> as_double(values.cells().begin(), values.cells().end());
    return layer_over(std::move(as_double), values.rows(), values.cols(), spec);
}

}  // namespace scenes
