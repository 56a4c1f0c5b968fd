#include "scenes/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/colormap.hpp"
#include "render/field.hpp"
#include "scenes/helpers/figure_caption.hpp"

namespace scenes {

// Each scene file's SceneInfo.
#define FIGGEN_SCENE(name) SceneInfo name##_scene();
#include "scenes/registry.inc"
#undef FIGGEN_SCENE

const std::vector<SceneInfo>& all_scenes() {
    static const std::vector<SceneInfo> all = {
#define FIGGEN_SCENE(name) name##_scene(),
#include "scenes/registry.inc"
#undef FIGGEN_SCENE
    };
    return all;
}

const SceneInfo& scene_of(const Description& d) {
    for (const SceneInfo& scene : all_scenes())
        if (scene.name == d.scene) return scene;
    std::string allowed;
    for (const SceneInfo& scene : all_scenes()) allowed += (allowed.empty() ? "" : ", ") + scene.name;
    throw SettingError("description.scene", "\"" + d.scene + "\"", "one of " + allowed);
}

const ExtraFile* extra_file(const Description& d, const std::string& format) {
    for (const ExtraFile& file : scene_of(d).extra_files)
        if (file.format == format) return &file;
    return nullptr;
}

std::string scenes_writing(const std::string& format) {
    std::string names;
    for (const SceneInfo& scene : all_scenes())
        for (const ExtraFile& file : scene.extra_files)
            if (file.format == format) {
                if (!names.empty()) names += ", ";
                names += scene.name;
            }
    return names;
}

std::unique_ptr<Scene> read_scene(const Description& d, const SceneOptions& options) {
    const SceneInfo& scene = scene_of(d);
    if (d.animation && d.animation->turn_frames > 0 && !scene.turns)
        throw SettingError("animation.turn_frames", std::to_string(d.animation->turn_frames),
                           "0: the scene " + d.scene + " draws no 3-D view to turn (3-D formula figures do)");
    // A caption that cannot fit is refused before the model is read or run.
    figure_caption(d, scaled(d.width, options.scale), scaled(d.height, options.scale), options.scale);
    return scene.read(d, options);
}

void apply_colormap(Description& d, const std::string& name) {
    const auto names = render::colormap_names();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        std::string allowed;
        for (const auto& n : names) allowed += (allowed.empty() ? "" : ", ") + n;
        throw UsageError("--cmap " + name + " is not allowed: use one of " + allowed);
    }
    const SceneInfo& scene = scene_of(d);
    if (scene.colormap_keys.empty()) {
        std::string fields;
        for (const SceneInfo& s : all_scenes())
            if (!s.colormap_keys.empty()) fields += std::string(fields.empty() ? "" : ", ") + s.name;
        throw UsageError("--cmap: " + d.id + " (scene " + d.scene + ") draws no field to colour; the field scenes are " +
                         fields);
    }
    for (const std::string& key : scene.colormap_keys_of ? scene.colormap_keys_of(d) : scene.colormap_keys) {
        d.style.insert_or_assign(key, name);
        const std::string prefix = key.substr(0, key.size() - std::string("colormap").size());
        d.style.erase(prefix + "colours");
        d.style.erase(prefix + "blend");  // how those colours were blended
        d.origins["style." + key] = "--cmap " + name;
    }
}

MemoryNeed grid_need(const std::string& what, double rows, double cols, double cell_bytes, double copies) {
    char text[96];
    std::snprintf(text, sizeof text, " %.0f x %.0f x %.0f", rows, cols, copies);
    return {what + text, rows * cols * cell_bytes * copies};
}

void require_drawable(Settings& section, const std::string& key, const std::string& what, double rows,
                      double cols) {
    const double most = render::max_texture_side;
    if (rows <= most && cols <= most) return;
    char text[256];
    std::snprintf(text, sizeof text, "%s at most %.0f cells a side (it would be %.0f x %.0f): the renderer draws one field that large",
                  what.c_str(), most, rows, cols);
    section.refuse(key, text);
}

std::string shown_steps(const std::vector<int>& steps) {
    std::string text = "[";
    for (std::size_t i = 0; i < steps.size(); ++i) text += (i ? ", " : "") + std::to_string(steps[i]);
    return text + "]";
}

void refuse_steps(const Description& d, const std::string& why, bool film_too) {
    if (!d.panels.empty()) throw SettingError("figure.panels", shown_steps(d.panels), "none: " + why);
    if (film_too && d.animation)
        throw SettingError("animation.steps", shown_steps({d.animation->first, d.animation->last}),
                           "none: the figure has no film; " + why);
}

int scaled(int pixels, double scale) {
    return std::max(2, static_cast<int>(std::lround(pixels * scale)));
}

int scaled_even(int pixels, double scale) {
    const int scaled = static_cast<int>(std::lround(pixels * scale));
    return std::max(2, scaled + (scaled % 2));
}

}  // namespace scenes
