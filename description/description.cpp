#include "description/description.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

#include "description/plain_name.hpp"

namespace description {
namespace {

const std::vector<Key> top_level_keys = {
    {"id", "the figure's id, also the output file name"},
    {"title", "one line for `figgen list`"},
    {"source", "the printed figure reproduced"},
    {"scene", "the scene that draws it"},
    {"model", "old name of scene"},
    {"seed", "seed of the random generator", "an integer", "an integer from 0 to 2^63-1"},
    {"caption", "decisions and notes"},
    {"original_caption", "the printed figure's own caption, in its document's language and script"},
    {"language", "the document's language, a fontconfig tag such as \"zh-cn\", \"ja\" or \"en\""},
    {"params", "[params] section"},
    {"style", "[style] section"},
    {"figure", "[figure] section"},
    {"animation", "[animation] section"},
};

const std::vector<Key> figure_keys = {
    {"panels", "steps shown in the panels, ascending"},
    {"size", "[width, height] in pixels"},
    {"panel_title", "title above each panel; {step} is the step shown"},
    {"formats", "vector files written besides the PNG: a list of \"pdf\" and \"svg\" (--format decides instead)"},
    {"columns", "panels a row; absent: as many as make the panels largest on the figure's size", "an integer",
     "an integer from 1 to 64"},
    {"caption", "a caption drawn beneath the figure: \"none\", \"title\" or \"original\" (original_caption)"},
};

const std::vector<Key> animation_keys = {
    {"steps", "[first, last] steps of the animation"},
    {"stride", "steps between frames", "an integer", "an integer from 1 to 100000000"},
    {"fps", "frames per second", "an integer", "an integer from 1 to 120"},
    {"segment_frames",
     "frames per film segment, each encoded on its own (from a key frame) and joined by stream "
     "copy: the unit spread over MPI ranks; 0 = one segment"},
    {"size", "[width, height] in pixels"},
    {"title", "title above each frame; {step} is the step shown"},
    {"poster",
     "the step whose frame is the film's poster (the still shown before it plays): the frame at that "
     "step or the last before it; default its last frame"},
    {"turn_frames",
     "frames after the run's that turn the camera once around the last step (3-D formula figures); 0 = none",
     "an integer", "an integer from 0 to 3600"},
};

// A command-line value as TOML would read it ("0.2" a float, "[1,2]" a list,
// "true" a boolean), or as a plain string when it is not TOML ("wrap").
toml::node_view<toml::node> parse_value(const std::string& text, toml::table& holder) {
    try {
        holder = toml::parse("v = " + text);
    } catch (const toml::parse_error&) {
        holder = toml::table{{"v", text}};
    }
    return holder["v"];
}

// The top-level keys that --set may give by their bare names.
bool is_top_level_override(const std::string& key) { return key == "id" || key == "title"; }

std::string section_of(const std::string& assignment) {
    const std::string key = assignment.substr(0, assignment.find('='));
    if (is_top_level_override(key)) return "description." + key;
    return key.find('.') == std::string::npos ? "params." + key : key;
}

// "section.key" -> "file:line" for every key written in the file.
void record_origins(const toml::table& root, const std::string& file, std::map<std::string, std::string>& origins) {
    auto at = [&](const toml::node& node) { return file + ":" + std::to_string(node.source().begin.line); };
    for (const auto& [key, node] : root) {
        if (const toml::table* section = node.as_table()) {
            origins[std::string(key.str())] = at(node);
            for (const auto& [inner, value] : *section)
                origins[std::string(key.str()) + "." + std::string(inner.str())] = at(value);
        } else {
            origins["description." + std::string(key.str())] = at(node);
        }
    }
}

}  // namespace

void apply_override(toml::table& root, const std::string& assignment) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        throw UsageError("--set " + assignment + ": expected key=value, e.g. --set r=0.2 or --set figure.panels=[0,5]");
    std::string key = assignment.substr(0, eq);
    if (is_top_level_override(key)) {  // --set id=NAME, --set title=TEXT: always text
        root.insert_or_assign(key, assignment.substr(eq + 1));
        return;
    }
    std::string section = "params";
    if (const auto dot = key.find('.'); dot != std::string::npos) {
        section = key.substr(0, dot);
        key = key.substr(dot + 1);
    }
    if (section != "params" && section != "style" && section != "figure" && section != "animation")
        throw UsageError("--set " + assignment + ": unknown section '" + section +
                         "'; allowed: params, style, figure, animation");
    if (!root.contains(section)) root.insert(section, toml::table{});
    toml::table* table = root[section].as_table();
    if (!table) throw UsageError("--set " + assignment + ": '" + section + "' is not a section");
    toml::table holder;
    auto value = parse_value(assignment.substr(eq + 1), holder);
    table->insert_or_assign(key, *value.node());
}

namespace {

std::pair<int, int> size_pair(Settings& s, const std::string& key, std::pair<int, int> fallback) {
    const auto v = s.integers(key, {fallback.first, fallback.second});
    if (v.size() != 2 || v[0] < 2 || v[1] < 2 || v[0] > max_figure_side || v[1] > max_figure_side)
        s.refuse(key, "[width, height], each 2.." + std::to_string(max_figure_side));
    return {static_cast<int>(v[0]), static_cast<int>(v[1])};
}

const toml::table& section_table(const toml::table& root, const char* name) {
    static const toml::table empty;
    const toml::node* node = root.get(name);
    if (!node) return empty;
    if (!node->is_table())
        throw SettingError(std::string(name), "a value", std::string("a [") + name + "] section");
    return *node->as_table();
}

void read_top_level(Description& d, const toml::table& root, std::optional<std::uint64_t> seed) {
    Settings top("description", root, top_level_keys);
    d.id = top.text("id", d.file.stem().string());
    if (!is_plain_id(d.id)) top.refuse("id", "\"" + printable(d.id) + "\"", plain_id_allowed);
    d.title = top.text("title", d.id);
    d.source = top.text("source", "");
    d.scene = top.text("scene", top.text("model", ""));
    d.caption = top.text("caption", "");
    d.original_caption = top.text("original_caption", "");
    d.language = top.text("language", "");
    if (!is_language_tag(d.language))
        top.refuse("language", "\"" + printable(d.language) + "\"",
                   "a language tag of lower-case letters, digits and hyphens, e.g. \"zh-cn\", \"zh-tw\", \"ja\" or \"en\"");
    const long long seed_value = top.integer("seed", 0);
    if (seed_value < 0) top.refuse("seed", "an integer from 0 to 2^63-1");
    d.seed = seed ? *seed : static_cast<std::uint64_t>(seed_value);
    if (d.scene.empty()) top.refuse("scene", "", "a scene name, e.g. scene = \"gray_scott\"");
    // Given by its old name: a mistake in it is reported at that line.
    if (!top.has("scene") && top.has("model")) d.origins["description.scene"] = d.origins["description.model"];
    d.params = section_table(root, "params");
    d.style = section_table(root, "style");
}

void read_figure(Description& d, const toml::table& root) {
    Settings figure("figure", section_table(root, "figure"), figure_keys);
    for (long long step : figure.integers("panels", {})) {
        if (step < 0 || step > 100'000'000) figure.refuse("panels", "steps from 0 to 100000000, ascending, each once");
        d.panels.push_back(static_cast<int>(step));
    }
    if (std::adjacent_find(d.panels.begin(), d.panels.end(), std::greater_equal<int>()) != d.panels.end())
        figure.refuse("panels", "steps from 0 to 100000000, ascending, each once");
    std::tie(d.width, d.height) = size_pair(figure, "size", {d.width, d.height});
    d.panel_title = figure.text("panel_title", d.panel_title);
    d.columns = figure.has("columns") ? figure.count_in("columns", 1, 1, 64) : 0;
    d.figure_caption = figure.text("caption", "none");
    if (d.figure_caption != "none" && d.figure_caption != "title" && d.figure_caption != "original")
        figure.refuse("caption", "\"" + printable(d.figure_caption) + "\"", "\"none\", \"title\" or \"original\"");
    if (d.figure_caption == "original" && d.original_caption.empty())
        figure.refuse("caption", "\"original\"",
                      "\"none\" or \"title\": the description has no original_caption (the printed figure's own "
                      "caption) to draw");
    for (const std::string& format : figure.texts("formats", {})) {
        if (format == "png") continue;  // always written
        if (format != "pdf" && format != "svg") figure.refuse("formats", "a list of \"pdf\", \"svg\" and \"png\"");
        if (std::find(d.formats.begin(), d.formats.end(), format) == d.formats.end()) d.formats.push_back(format);
    }
}

void read_animation(Description& d, const toml::table& root) {
    if (!root.contains("animation")) return;
    Settings anim("animation", section_table(root, "animation"), animation_keys);
    Animation a;
    const auto steps = anim.integers("steps", {0, 0});
    if (steps.size() != 2 || steps[0] < 0 || steps[1] < steps[0] || steps[1] > 100'000'000)
        anim.refuse("steps", "[first, last] with 0 <= first <= last <= 100000000");
    a.first = static_cast<int>(steps[0]);
    a.last = static_cast<int>(steps[1]);
    a.stride = anim.count_in("stride", a.stride, 1, 100'000'000);
    a.fps = anim.count_in("fps", a.fps, 1, 120);
    a.segment_frames = anim.count_in("segment_frames", a.segment_frames, 0, 100'000'000);
    std::tie(a.width, a.height) = size_pair(anim, "size", {a.width, a.height});
    a.title = anim.text("title", a.title);
    a.turn_frames = anim.count_in("turn_frames", a.turn_frames, 0, 3600);
    if (anim.has("poster")) {
        // As ffmpeg's -ss seeks: the frame at that step, else the last before it.
        const long long poster = anim.integer("poster", a.last);
        if (poster < a.first || poster > a.last)
            anim.refuse("poster", "a step from " + std::to_string(a.first) + " to " + std::to_string(a.last) +
                                      " (animation.steps); the poster is the frame at that step or the last "
                                      "before it");
        a.poster = static_cast<int>(poster);
    }
    d.animation = a;
}

}  // namespace

std::string Description::where(const std::string& key) const {
    // "params.plants[1].axiom" -> "params.plants[1]" -> "params.plants" -> "params"
    for (std::string k = key; !k.empty();) {
        if (const auto found = origins.find(k); found != origins.end()) return found->second;
        const auto cut = k.find_last_of(".[");
        if (cut == std::string::npos) break;
        k.resize(cut);
    }
    return file.filename().string();
}

int Description::last_step(bool with_animation) const {
    int last = panels.empty() ? 0 : panels.back();
    if (with_animation && animation) last = std::max(last, animation->last);
    return last;
}

std::string expand(const std::string& pattern, const std::vector<std::pair<std::string, std::string>>& values) {
    std::string text = pattern;
    for (const auto& [name, value] : values) {
        const std::string field = "{" + name + "}";
        for (auto at = text.find(field); at != std::string::npos; at = text.find(field, at + value.size()))
            text.replace(at, field.size(), value);
    }
    return text;
}

std::string format_step(const std::string& pattern, int step) {
    return expand(pattern, {{"step", std::to_string(step)}});
}

Description load_description(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                             std::optional<std::uint64_t> seed) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw UsageError("cannot read " + printable(file.string()));
    // At most one byte more than allowed is read, so neither a huge file nor
    // an endless one (a FIFO, /dev/zero) is taken into memory.
    std::string text;
    char chunk[1 << 16];
    while (text.size() <= max_description_bytes && in.read(chunk, sizeof chunk).gcount() > 0)
        text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (in.bad()) throw UsageError("cannot read " + printable(file.string()));
    return parse_description(text, file, overrides, seed);
}

Description parse_description(std::string_view text, const std::filesystem::path& file,
                              const std::vector<std::string>& overrides, std::optional<std::uint64_t> seed) {
    // Read from a file or given as text (the Python module): the same bound.
    if (text.size() > max_description_bytes)
        throw UsageError(printable(file.string()) + ": a description is at most 16 MiB; this one is larger");
    toml::table root;
    try {
        root = toml::parse(text, file.string());
    } catch (const toml::parse_error& e) {
        std::ostringstream message;
        message << file.string() << ":" << e.source().begin.line << ": " << e.description();
        throw UsageError(message.str());
    }
    std::map<std::string, std::string> origins;
    record_origins(root, file.filename().string(), origins);
    return description_from_table(std::move(root), file, std::move(origins), overrides, seed);
}

Description description_from_table(toml::table root, const std::filesystem::path& file,
                                   std::map<std::string, std::string> origins,
                                   const std::vector<std::string>& overrides, std::optional<std::uint64_t> seed) {
    Description d;
    d.file = file;
    d.origins = std::move(origins);
    for (const std::string& assignment : overrides) {
        apply_override(root, assignment);
        // As a one-line message may show it: a --set title may be any bytes, and long.
        d.origins[section_of(assignment)] = "--set " + printable_short(assignment, 100);
    }
    at_source(d, [&] {
        read_top_level(d, root, seed);
        read_figure(d, root);
        read_animation(d, root);
    });
    return d;
}

}  // namespace description
