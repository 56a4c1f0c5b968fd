#include "figures/field_spec.hpp"

#include <algorithm>

namespace figures {

std::vector<Key> field_spec_keys(const std::string& prefix) {
    return {
        {prefix + "colormap", "Reds, Blues, Greens, viridis, inferno, magma, plasma or cividis (--cmap)"},
        {prefix + "colours", "a list of colours for the states 0, 1, ... (#rrggbb or names), instead of colormap"},
        {prefix + "vmin", "value of the first colour; absent: the panel's minimum"},
        {prefix + "vmax", "value of the last colour; absent: the panel's maximum"},
        {prefix + "alpha", "opacity over what lies below, 0..1"},
        {prefix + "sampling", "\"nearest\" or \"smooth\""},
    };
}

FieldSpec read_field_spec(Settings& style, const FieldSpec& defaults, const std::string& prefix) {
    FieldSpec spec = defaults;
    try {
        if (style.has(prefix + "colours")) {
            std::vector<glm::vec3> colours;
            for (const std::string& c : style.texts(prefix + "colours", {})) colours.push_back(render::parse_colour(c));
            spec.colormap = render::listed_colormap("listed", colours);
        } else {
            spec.colormap = render::colormap(style.text(prefix + "colormap", defaults.colormap.name));
        }
    } catch (const std::invalid_argument& e) {
        throw UsageError("style." + prefix + "colormap: " + e.what());
    }
    if (style.has(prefix + "vmin")) spec.vmin = style.number(prefix + "vmin", 0);
    if (style.has(prefix + "vmax")) spec.vmax = style.number(prefix + "vmax", 1);
    if (spec.vmin && spec.vmax && !(*spec.vmax > *spec.vmin))
        throw UsageError("style." + prefix + "vmax must be greater than style." + prefix + "vmin");
    const double alpha = style.number(prefix + "alpha", defaults.alpha);
    if (alpha < 0 || alpha > 1)
        throw UsageError("style." + prefix + "alpha = " + std::to_string(alpha) + " is not allowed: expected 0..1");
    spec.alpha = static_cast<float>(alpha);
    const std::string sampling =
        style.text(prefix + "sampling", defaults.sampling == render::Sampling::smooth ? "smooth" : "nearest");
    if (sampling != "nearest" && sampling != "smooth")
        throw UsageError("style." + prefix + "sampling = \"" + sampling +
                         "\" is not allowed: use \"nearest\" or \"smooth\"");
    spec.sampling = sampling == "smooth" ? render::Sampling::smooth : render::Sampling::nearest;
    return spec;
}

FieldLayer field_layer(const sim::Grid<double>& values, const FieldSpec& spec) {
    FieldLayer layer{values.rows(), values.cols(), values.cells(), {}};
    const auto [lo, hi] = std::minmax_element(layer.values.begin(), layer.values.end());
    double vmin = spec.vmin.value_or(*lo), vmax = spec.vmax.value_or(*hi);
    // matplotlib maps everything to the first colour when the range is empty.
    if (!(vmax > vmin)) vmax = vmin + 1;
    layer.style = {&spec.colormap, vmin, vmax, spec.alpha, spec.sampling};
    return layer;
}

FieldLayer field_layer(const sim::Grid<std::uint8_t>& values, const FieldSpec& spec) {
    sim::Grid<double> as_double(values.rows(), values.cols());
    std::copy(values.cells().begin(), values.cells().end(), as_double.data());
    return field_layer(as_double, spec);
}

}  // namespace figures
