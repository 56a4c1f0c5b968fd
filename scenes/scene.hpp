#pragma once
// Scenes: the only code that knows both a model (sim/) and how to draw it
// (render/). A scene works in three phases:
//   1. read:  its reader (SceneInfo::read) reads and checks every setting of
//             the description (model parameters, style, sizes, steps,
//             colours, estimates); a mistake is a SettingError, and nothing
//             has run;
//   2. run:   Scene::render runs the model once, to the last step any output
//             needs;
//   3. draw:  and draws the figure and film into the Output.
// render() is const: a setting can be neither read nor refused after phase 1.

#include <memory>
#include <string>
#include <vector>

#include "render/ticks.hpp"
#include "scenes/description_names.hpp"
#include "scenes/output.hpp"

namespace scenes {

// What the command asks of every scene.
struct SceneOptions {
    double scale = 1.0;  // multiplies every size in pixels
    bool film = true;    // the animation is wanted (MP4 or PNG sequence)
    int threads = 1;     // work items that may run at once (for memory estimates: each holds its own buffers)
    bool strict = false;  // a model's timestep past its stability bound is refused (check_run), not said
    bool error = false;   // a formula model's error in time is measured (--error)
};

// One big allocation of a model, for the command's memory estimate.
struct MemoryNeed {
    std::string what;  // e.g. "grids of doubles 4096 x 4096 x 6"
    double bytes;
};
// A need of `copies` rows x cols grids of `cell_bytes` each.
MemoryNeed grid_need(const std::string& what, double rows, double cols, double cell_bytes, double copies);

class Scene {
public:
    virtual ~Scene() = default;
    // The model's largest allocations (phase 1's estimate, checked by the
    // command against --max-memory before render()).
    virtual std::vector<MemoryNeed> memory() const { return {}; }
    // The model's work items when its run splits into independent ones
    // (scenes/work_items.hpp); render() then gets their results from
    // Output::results. Null for a scene that runs as one piece.
    virtual const WorkItems* work() const { return nullptr; }
    // The end of phase 1, once the description's stored arrays (a Ready
    // pattern's start) are decoded: the checks that need the model's start.
    // Throws a SettingError; nothing has run.
    virtual void check_run() const {}
    // Phases 2 and 3: runs the model and writes every output into `out`.
    virtual void render(Output& out) const = 0;
};

// What every scene keeps from phase 1: its description, the command's
// options, and its [params] and [style] sections as read (their used()
// values go into the metadata). Built before the scene's own members, which
// are read from them.
class SceneBase : public Scene {
protected:
    SceneBase(const Description& d, const SceneOptions& options, std::vector<Key> param_keys,
              std::vector<Key> style_keys)
        : d_(d),
          options_(options),
          params_("params", d.params, std::move(param_keys)),
          style_("style", d.style, std::move(style_keys)) {}

    const Description& d_;
    const SceneOptions options_;
    Settings params_, style_;
};

// A scene's phase 1: reads and checks `d`'s settings.
using SceneReader = std::unique_ptr<Scene> (*)(const Description& d, const SceneOptions& options);

// What the catalog says of a key number: shown when `when` holds ("" always).
struct KeyReference {
    const char* when;
    const char* text;  // as shown, e.g. "1.896 (91/48, the incipient cluster)"
};

// One key number of a scene's metadata, as a gallery card shows it
// (app/gallery/key_numbers.hpp reads them).
//
// Conditions (KeyReference::when, KeyNumber::only) are "field=value" tests
// joined by ",", all of which must hold: `field` is a field of the array
// element a "*" reached, or a pointer into the whole metadata when it
// starts with "/"; `value` may list alternatives, "q=0.55|0.6|0.65";
// "!field" holds when the field is absent. Numbers compare to 1e-9.
//
// Labels take "{field}" (the element's field), "{#}" (the element's place,
// from 1) and "{field|text}" (text where the element has the field).
struct KeyNumber {
    const char* path;  // JSON pointer; a "*" step runs over every element of an array
    const char* label;
    const char* kind;  // "number"; "integer"; "range": first to last of a list;
                       // "bounds": [xmin, xmax, ymin, ymax]; "count": a list's length
    const char* unit;  // after the value, or ""
    std::vector<KeyReference> references = {};
    const char* only = "";   // show only the elements for which this holds
    const char* error = "";  // a sibling field holding the value's standard error: "value ± error"
    int digits = 4;          // significant digits of a "number"
};

// A file a scene can write besides the figure and its film, chosen by
// --format NAME: Ready's VTI of a formula run's last step. The scene hands
// its content over in the FigureDrawing; the command writes it.
struct ExtraFile {
    std::string format;  // --format's word: "vti"
    // The most the file takes on disk for this description, from the
    // scene's own keys and their limits.
    double (*disk)(const Description& d) = nullptr;
};

// A scene: each scene file defines its own (`SceneInfo diffusion_scene()`),
// and scenes/registry.inc lists them, one line each. What the command needs
// to know of a scene it learns here, never by the scene's name.
struct SceneInfo {
    std::string name;  // the description's `scene`
    SceneReader read;
    // The [style] keys naming its fields' colormaps: what --cmap sets
    // (empty: the scene draws no field). A key "X" comes with "X"'s sibling
    // list of colours, "colours" or "a_colours", which --cmap removes.
    std::vector<std::string> colormap_keys = {};
    // Its key numbers, in the order of the card, with the catalog's
    // reference values (docs/catalog.md).
    std::vector<KeyNumber> key_numbers = {};
    // Those of colormap_keys that this description has (a formula's
    // chemicals: only its rule's); null: all of them.
    std::vector<std::string> (*colormap_keys_of)(const Description& d) = nullptr;
    // The files it can write besides the figure and film (--format).
    std::vector<ExtraFile> extra_files = {};
    // Whether its films can turn the camera round the last step
    // (animation.turn_frames); its reader refuses the figures that cannot.
    bool turns = false;
};

const std::vector<SceneInfo>& all_scenes();

// Phase 1 for `d`: its scene, every setting read and checked. Throws
// SettingError (key, value, what is allowed) for any mistake; `d` must
// outlive the scene.
std::unique_ptr<Scene> read_scene(const Description& d, const SceneOptions& options);

// Sets every colormap of a field figure to `name` (--cmap); throws
// UsageError for an unknown colormap or a figure without a field.
void apply_colormap(Description& d, const std::string& name);

// The scene of `d` (SettingError for an unknown one).
const SceneInfo& scene_of(const Description& d);
// The file `format` (--format's word) that d's scene writes besides its
// figure, or null when it writes none.
const ExtraFile* extra_file(const Description& d, const std::string& format);
// The scenes that write the file `format`: "formula, ...".
std::string scenes_writing(const std::string& format);

// Refuses `key` of `section` (SettingError) when it makes a field of rows x
// cols cells that the renderer cannot hold as one texture; `what` names the
// field, e.g. "the deposit's view".
void require_drawable(Settings& section, const std::string& key, const std::string& what, double rows,
                      double cols);

// Steps as a message shows them: "[16, 200]".
std::string shown_steps(const std::vector<int>& steps);
// Refuses figure.panels (and, with `film_too`, an [animation]) of a figure
// that has no steps to show; `why` says what it shows instead.
void refuse_steps(const Description& d, const std::string& why, bool film_too);

// A figure's pixel size at the given scale: rounded, at least 2.
int scaled(int pixels, double scale);
// A film's pixel size at the given scale, rounded up to even (what H.264 in
// yuv420p needs); the film's JSON says when that changed it (animation.size_rounded).
int scaled_even(int pixels, double scale);
using render::format_fixed;  // numbers shown on a figure, "1.57"

}  // namespace scenes
