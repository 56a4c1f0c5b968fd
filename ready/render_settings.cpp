// Ready's <render_settings> as [style]: the active chemical through its colour map.
#include "ready/reading.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ready::reading {

namespace {

std::string hex(double r, double g, double b) {
    char text[8];
    const auto c = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
    std::snprintf(text, sizeof text, "#%02x%02x%02x", c(r), c(g), c(b));
    return text;
}

}  // namespace

toml::table style_of(const XMLElement* rs, int chemicals) {
    const auto value = [&](const char* name) -> const XMLElement* { return child(rs, name); };
    std::string active = "a";
    if (const XMLElement* e = value("active_chemical")) active = text_attribute(e, "value", "a");
    if (!is_chemical(active, chemicals)) active.assign(1, 'a');  // not = "a": GCC 12's -Wrestrict misfires on it
    double low = 0, high = 1;
    if (const XMLElement* e = value("low")) low = as_float(attribute(e, "value", 0));
    if (const XMLElement* e = value("high")) high = as_float(attribute(e, "value", 1));
    if (!(high > low)) high = low + 1;
    std::string map = "spectral";
    if (const XMLElement* e = value("colormap")) map = text_attribute(e, "value", map);
    bool bar = true;
    if (const XMLElement* e = value("show_color_scale")) bar = text_attribute(e, "value", "true") == "true";
    toml::table s{{"show", toml::array{active}}};
    const std::string p = active + "_";
    // Brewer's Spectral (9), red to blue, and Ready's terrain.
    static const std::vector<std::string> spectral = {"#d53e4f", "#f46d43", "#fdae61", "#fee08b", "#ffffbf",
                                                      "#e6f598", "#abdda4", "#66c2a5", "#3288bd"};
    static const std::vector<std::string> terrain = {"#333399", "#0099ff", "#00cc66", "#ffff99", "#805c54", "#ffffff"};
    std::vector<std::string> colours;
    std::string blend = "rgb";
    bool reverse = false;
    if (map == "HSV blend") {
        double r = 0, g = 0, b = 1, r2 = 1, g2 = 0, b2 = 0;
        if (const XMLElement* e = value("color_low")) r = attribute(e, "r", 0), g = attribute(e, "g", 0), b = attribute(e, "b", 1);
        if (const XMLElement* e = value("color_high")) r2 = attribute(e, "r", 1), g2 = attribute(e, "g", 0), b2 = attribute(e, "b", 0);
        colours = {hex(r, g, b), hex(r2, g2, b2)};
        blend = "hsv";
    } else if (map == "inferno" || map == "inferno reversed") {
        s.insert(p + "colormap", "inferno");
    } else if (map == "terrain" || map == "terrain reversed") {
        colours = terrain;
        reverse = map == "terrain reversed";
    } else {  // spectral, Ready's default: blue at low; "spectral reversed": red at low
        colours = spectral;
        reverse = map != "spectral reversed";
    }
    if (reverse) std::reverse(colours.begin(), colours.end());
    if (!colours.empty()) {
        toml::array list;
        for (const auto& c : colours) list.push_back(c);
        s.insert(p + "colours", std::move(list));
        s.insert(p + "blend", blend);
    }
    s.insert(p + "vmin", low);
    s.insert(p + "vmax", high);
    s.insert(p + "colour_bar", bar);
    s.insert(p + "sampling", "nearest");
    // The level of a 3-D grid's isosurface (the scene's default is Ready's 0.25).
    if (const XMLElement* e = value("contour_level")) {
        const double level = as_float(attribute(e, "value", 0.25));
        if (std::isfinite(level) && std::fabs(level) <= 1e30) s.insert("contour_level", level);
    }
    if (const XMLElement* e = value("invert_contour_cap"))
        if (text_attribute(e, "value", "false") == "true") s.insert("contour_inside", "below");
    return s;
}

}  // namespace ready::reading
