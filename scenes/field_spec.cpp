#include "scenes/field_spec.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace scenes {

std::vector<Key> field_spec_keys(const std::string& prefix) {
    return {
        {prefix + "colormap", "Reds, Blues, Greens, viridis, inferno, magma, plasma or cividis (--cmap)"},
        {prefix + "colours", "a list of colours for the states 0, 1, ... (#rrggbb or names), instead of colormap"},
        {prefix + "blend", "\"none\": one colour of colours a state; \"rgb\" or \"hsv\": colours are stops of a smooth "
                           "ramp, blended in RGB or HSV (Ready's \"HSV blend\")"},
        {prefix + "vmin", "value of the first colour; absent: the panel's minimum"},
        {prefix + "vmax", "value of the last colour; absent: the panel's maximum"},
        {prefix + "alpha", "opacity over what lies below, 0..1"},
        {prefix + "sampling", "\"nearest\" or \"smooth\""},
        {prefix + "colour_bar", "a colour bar with ticks beside each panel, true or false"},
        {prefix + "colour_bar_label", "the colour bar's label"},
    };
}

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

render::Colormap read_colormap(Settings& style, const FieldSpec& defaults, const std::string& prefix) {
    std::optional<render::Colormap> listed;
    if (style.has(prefix + "colours")) {
        std::vector<glm::vec3> colours;
        for (const std::string& c : style.texts(prefix + "colours", {})) {
            const auto colour = render::find_colour(c);
            if (!colour)
                style.refuse(prefix + "colours", "\"" + c + "\"", "colours, each " + render::colours_allowed());
            colours.push_back(*colour);
        }
        if (colours.empty() || colours.size() > 4096) style.refuse(prefix + "colours", "1 to 4096 colours");
        // Read only when given: figures without it keep their metadata.
        const std::string blend = style.has(prefix + "blend") ? style.text(prefix + "blend", "none") : "none";
        if (blend != "none" && blend != "rgb" && blend != "hsv")
            style.refuse(prefix + "blend", "\"none\", \"rgb\" or \"hsv\"");
        listed = render::listed_colormap("listed", blend == "none" ? colours : ramp(colours, blend == "hsv"));
    } else if (style.has(prefix + "blend")) {
        style.refuse(prefix + "blend", "only beside " + prefix + "colours, the stops it blends");
    }
    // Read whenever given, so that a bad name is refused beside colours too.
    if (!listed || style.has(prefix + "colormap")) {
        const std::string name = style.text(prefix + "colormap", defaults.colormap.name);
        const render::Colormap* map = render::find_colormap(name);
        if (!map && name != defaults.colormap.name) {  // not a scene's own listed map either
            std::string allowed;
            for (const auto& n : render::colormap_names()) allowed += (allowed.empty() ? "" : ", ") + n;
            style.refuse(prefix + "colormap", "one of " + allowed);
        }
        // One of the two: a colormap given beside colours would be ignored in silence.
        if (listed)
            style.refuse(prefix + "colormap", "no colormap where " + prefix +
                                                   "colours gives the colours: give one of the two (--cmap replaces "
                                                   "colours)");
        return map ? *map : defaults.colormap;
    }
    return *listed;
}

}  // namespace

FieldSpec read_field_spec(Settings& style, const FieldSpec& defaults, const std::string& prefix) {
    FieldSpec spec = defaults;
    spec.colormap = read_colormap(style, defaults, prefix);
    if (style.has(prefix + "vmin")) spec.vmin = style.number(prefix + "vmin", 0);
    if (style.has(prefix + "vmax")) spec.vmax = style.number(prefix + "vmax", 1);
    if (spec.vmin && spec.vmax && !(*spec.vmax > *spec.vmin))
        style.refuse(prefix + "vmax", "a number greater than " + prefix + "vmin = " + description::shown(*spec.vmin));
    spec.alpha = static_cast<float>(style.number_in(prefix + "alpha", defaults.alpha, 0.0, 1.0));
    const std::string sampling =
        style.text(prefix + "sampling", defaults.sampling == render::Sampling::smooth ? "smooth" : "nearest");
    if (sampling != "nearest" && sampling != "smooth") style.refuse(prefix + "sampling", "\"nearest\" or \"smooth\"");
    spec.sampling = sampling == "smooth" ? render::Sampling::smooth : render::Sampling::nearest;
    spec.colour_bar = style.flag(prefix + "colour_bar", defaults.colour_bar);
    spec.colour_bar_label = style.text(prefix + "colour_bar_label", defaults.colour_bar_label);
    return spec;
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
