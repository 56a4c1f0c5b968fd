// Ready's rules on meshes (its MeshRD): a formula or a whole kernel run on
// the cells of a mesh (sim/kernel/run.hpp's MeshRun), each cell's
// neighbours Ready's (sim/mesh/mesh.hpp), and drawn as people look at
// them: a surface in space (the Stanford bunny) lit and shaded, coloured
// by the chemical; a flat tiling (Penrose's rhombi, triangles, hexagons) as
// its polygons filled by state with thin edges, in vector output too; a
// lattice of solid cells as the cells at or above the middle of the range,
// inside the lattice's box, from a three-quarter view above.
// The mesh and the cells' start come from the Ready pattern file (.vtu)
// that is rendered: a description file cannot name a file to read.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>

#include "description/catalog.hpp"
#include "description/stored_mesh.hpp"
#include "ready/pattern.hpp"
#include "render/plot.hpp"
#include "render/shapes.hpp"
#include "render/text.hpp"
#include "render/tubes.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/formula_model.hpp"
#include "scenes/helpers/formula_style.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"
#include "sim/formula/names.hpp"
#include "sim/formula/overlays.hpp"
#include "sim/formula/rule.hpp"
#include "sim/random.hpp"
#include "sim/kernel/run.hpp"
#include "sim/mesh/mesh.hpp"

namespace scenes {
namespace {

namespace formula = sim::formula;
namespace mesh = sim::mesh;

struct MeshModel {
    int chemicals = 2;
    std::string formula, kernel;
    bool float64 = false;
    mesh::Kind neighbourhood = mesh::Kind::vertex;
    int steps = 1000;
    std::string mesh;  // one of figgen's meshes (figures/meshes/NAME.vtu), where no pattern file gives one
    std::vector<std::pair<std::string, double>> parameters;
    bool zero_first = true;
    std::vector<toml::table> initial;  // the start's overlays, over the stored cells
};

const Schema<MeshModel> model_schema = [] {
    Schema<MeshModel> s;
    s.count("chemicals", &MeshModel::chemicals, "how many chemicals the rule has: a, b, c, ...", 1, formula::max_chemicals);
    s.key({"formula", "the rule as Ready's formula on a mesh: laplacian_a is over the cell's neighbours (docs/kernels.md)",
           "text", "a formula; or give kernel"},
          [](Settings& p, const std::string& key, MeshModel& m) {
              if (!p.has(key)) return;
              m.formula = p.text(key, "");  // text, or refused naming it
              if (p.has("kernel")) return;  // the kernel's reader refuses both
              if (m.formula.empty()) p.refuse(key, "\"\"", "a formula, e.g. \"delta_a = laplacian_a;\"");
          });
    s.key({"kernel", "the rule as a whole OpenCL C kernel on the mesh's cells (docs/kernels.md)", "text",
           "a __kernel void rd_compute(...) in the OpenCL C figgen reads"},
          [](Settings& p, const std::string& key, MeshModel& m) {
              if (!p.has(key)) {
                  if (!p.has("formula")) p.refuse(key, "", "a kernel, or else a formula");
                  return;
              }
              m.kernel = p.text(key, "");  // text, or refused naming it
              if (p.has("formula")) p.refuse(key, "no kernel where params.formula is given: a rule is one or the other");
              if (m.kernel.empty()) p.refuse(key, "\"\"", "a __kernel void rd_compute(...)");
          });
    s.choice("data_type", &MeshModel::float64, {{"float", false}, {"double", true}},
             "the numbers: float (Ready's Float32) or double (Float64)");
    s.choice("neighborhood", &MeshModel::neighbourhood,
             {{"vertex", mesh::Kind::vertex}, {"edge", mesh::Kind::edge}, {"face", mesh::Kind::face}},
             "a cell's neighbours: the cells sharing a corner (vertex), an edge, or a face (Ready's neighborhood_type)");
    s.count("steps", &MeshModel::steps, "how many steps the model runs", 0, 10'000'000);
    s.key({"mesh", "the mesh: one of figgen's own (figures/meshes/NAME.vtu, by NAME); a Ready .vtu pattern rendered "
                   "as it is gives its own",
           "text", "the name of one of figgen's meshes, e.g. \"bunny\""},
          [](Settings& p, const std::string& key, MeshModel& m) {
              if (!p.has(key)) return;
              m.mesh = p.text(key, "");
              const bool plain = !m.mesh.empty() && m.mesh.size() <= 64 &&
                                 std::all_of(m.mesh.begin(), m.mesh.end(), [](char c) {
                                     return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) ||
                                            c == '-' || c == '_';
                                 });
              if (!plain) p.refuse(key, "the name of one of figgen's meshes: a-z, 0-9, - and _");
          });
    s.key({"zero_first", "the start is all zero before the overlays (where there are overlays)", "true or false", "", true},
          [](Settings& p, const std::string& key, MeshModel& m) { m.zero_first = p.flag(key, true); });
    s.key({"initial", "the start: Ready's overlays in order over the mesh's cells, each sampled at its centre",
           "a list of tables", "at most 1000 overlays"},
          [](Settings& p, const std::string& key, MeshModel& m) {
              m.initial = p.tables(key);
              if (m.initial.size() > 1000) p.refuse(key, "at most 1000 overlays");
          });
    return s;
}();

bool is_key(const std::vector<Key>& keys, const std::string& name) {
    return std::any_of(keys.begin(), keys.end(), [&](const Key& k) { return k.name == name; });
}

std::vector<Key> mesh_param_keys(const Description& d) {
    std::vector<Key> keys = model_schema.keys();
    const std::vector<Key> own = keys;
    for (const auto& [key, value] : d.params) {
        const std::string name(key.str());
        if (!is_key(own, name)) keys.push_back({name, "a parameter of the formula", "a number", numbers_allowed(-1e30, 1e30)});
    }
    return keys;
}

int mesh_chemicals(const Description& d) {
    const auto count = d.params["chemicals"].value<long long>();
    return count ? static_cast<int>(std::clamp<long long>(*count, 1, formula::max_chemicals)) : 2;
}

// figgen's own meshes: the .vtu files of the catalog's meshes/ folder,
// named by their stems. A description names one, never a path: the name is
// looked up among the files there.
std::vector<std::string> catalog_mesh_names() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(description::catalog_dir() / "meshes", ec))
        if (e.path().extension() == ".vtu") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string catalog_meshes_said() {
    std::string said;
    for (const std::string& n : catalog_mesh_names()) said += (said.empty() ? "\"" : ", \"") + n + "\"";
    return said.empty() ? "none installed" : said;
}

// The catalog's mesh `name`, or null where there is none of that name;
// throws description::FileError where its file cannot be read. Read once a
// process: a description's scene is read again for every check (figgen
// describe, the estimates, the render).
std::shared_ptr<const description::StoredMesh> catalog_mesh_named(const std::string& name) {
    const std::vector<std::string> names = catalog_mesh_names();
    if (std::find(names.begin(), names.end(), name) == names.end()) return nullptr;
    static std::mutex lock;
    static std::map<std::string, std::shared_ptr<const description::StoredMesh>> read;
    const std::lock_guard<std::mutex> held(lock);
    if (const auto known = read.find(name); known != read.end()) return known->second;
    const ready::Pattern p = ready::read_pattern(description::catalog_dir() / "meshes" / (name + ".vtu"));
    if (p.mesh) read[name] = p.mesh;
    return p.mesh;
}

struct Style {
    FormulaStyle chemicals;
    double azimuth = 0, elevation = 15;  // a surface's or a lattice's view, degrees
    double edge_width = 0.5;             // a tiling's edges, pixels (0: none)
};

Schema<Style> style_schema(int chemicals) {
    Schema<Style> s;
    s.part_at(
        formula_style_schema(chemicals), [](auto& v) -> auto& { return v.chemicals; });
    s.number("azimuth", &Style::azimuth,
             "a surface's or a solid lattice's view: degrees about y (0: from +z; by default 0, or a three-quarter "
             "view of a mesh half as long again one way as the other, and 35 for a solid lattice)",
             -360, 360);
    s.number("elevation", &Style::elevation,
             "the same view's degrees above the horizontal (by default 15, and 25 for a solid lattice)", -89, 89);
    s.number("edge_width", &Style::edge_width, "a flat tiling's cell edges, pixels before --scale (under half a pixel: none)", 0, 10);
    return s;
}

Style style_defaults(int chemicals) {
    Style s;
    s.chemicals = formula_style_defaults(chemicals);
    return s;
}

// The view about y when the description gives none: from +z (0) for a
// mesh about as deep as it is wide (the bunny, a lattice); a three-quarter
// view of one at least half as long again one way as the other (the lion
// and the zebra, long in z, are seen from their side and front, not from
// the front alone).
double default_azimuth(const sim::mesh::Mesh& m) {
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (std::size_t p = 0; p < m.point_count(); ++p)
        for (int k = 0; k < 3; ++k) {
            const double v = m.points[3 * p + static_cast<std::size_t>(k)];
            lo[k] = p == 0 ? v : std::min(lo[k], v);
            hi[k] = p == 0 ? v : std::max(hi[k], v);
        }
    const double wide = hi[0] - lo[0], deep = hi[2] - lo[2];
    if (deep > 1.5 * wide) return 55;
    if (wide > 1.5 * deep) return 35;
    return 0;
}

// How a mesh is drawn: by the dimension of its cells and where its points lie.
enum class Look { surface, tiling, solid };

bool solid_type(std::uint8_t t) {
    return t == mesh::cell_type::tetra || t == mesh::cell_type::voxel || t == mesh::cell_type::hexahedron ||
           t == mesh::cell_type::wedge || t == mesh::cell_type::pyramid || t == mesh::cell_type::polyhedron;
}

Look look_of(const mesh::Mesh& m) {
    bool solid = false;
    for (std::uint8_t t : m.types) solid = solid || solid_type(t);
    if (solid) return Look::solid;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, span = 0;
    for (std::size_t p = 0; p < m.point_count(); ++p) {
        lo = std::min(lo, m.points[3 * p + 2]), hi = std::max(hi, m.points[3 * p + 2]);
        span = std::max({span, std::fabs(m.points[3 * p]), std::fabs(m.points[3 * p + 1])});
    }
    return hi - lo <= 1e-9 * std::max(1.0, span) ? Look::tiling : Look::surface;
}

const char* look_name(Look l) { return l == Look::surface ? "surface" : l == Look::tiling ? "tiling" : "solid"; }

// The kernel Ready's formula rule on a mesh is, its lines counted from the
// formula's: a message about the generated kernel is said of the formula.
std::string said_of_formula(const std::string& what, int formula_first_line) {
    const std::string head = "kernel line ";
    if (what.rfind(head, 0) != 0) return what;
    std::size_t end = head.size();
    int line = 0;
    while (end < what.size() && std::isdigit(static_cast<unsigned char>(what[end]))) line = line * 10 + (what[end++] - '0');
    if (line < formula_first_line) return "the kernel figgen makes of the formula, line " + std::to_string(line) + what.substr(end);
    return "formula line " + std::to_string(line - formula_first_line + 1) + what.substr(end);
}

class MeshScene : public SceneBase {
public:
    MeshScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, mesh_param_keys(d),
                    style_schema(mesh_chemicals(d)).keys(style_defaults(mesh_chemicals(d)))),
          m_(read_model(d)),
          s_(style_schema(m_.chemicals).read(style_, style_defaults(m_.chemicals))),
          spec_(shown_specs(s_.chemicals).front()) {
        if (d.panels.empty()) throw SettingError("figure.panels", "[]", "the steps to show, e.g. [0, 500, 1000]");
        if (d.panels.back() > m_.steps)
            throw SettingError("figure.panels", "...", "steps up to params.steps (" + std::to_string(m_.steps) + ")");
        if (options.film && d.animation && d.animation->last > m_.steps)  // --no-video: no film to check
            throw SettingError("animation.steps", std::to_string(d.animation->last),
                               "steps up to params.steps (" + std::to_string(m_.steps) + ")");
        const description::StoredMesh& stored = *mesh_;
        cells_mesh_.points = stored.points;
        cells_mesh_.offsets = stored.offsets;
        cells_mesh_.point_ids = stored.point_ids;
        cells_mesh_.types = stored.types;
        cells_mesh_.faces = stored.faces;
        cells_mesh_.face_offsets = stored.face_offsets;
        look_ = look_of(cells_mesh_);
        // A solid lattice from a three-quarter view above, as a 3-D grid's isosurface is seen.
        azimuth_ = style_.has("azimuth") ? s_.azimuth : look_ == Look::solid ? 35 : default_azimuth(cells_mesh_);
        elevation_ = style_.has("elevation") || look_ != Look::solid ? s_.elevation : 25;
        try {
            neighbours_ = mesh::neighbours(cells_mesh_, m_.neighbourhood);
        } catch (const std::invalid_argument& e) {
            throw SettingError("params.neighborhood", "...", std::string("a mesh figgen can take: ") + e.what());
        }
        formula::Rule for_overlays;
        for_overlays.chemicals = m_.chemicals;
        for_overlays.parameters = m_.parameters;
        overlays_.zero_first = m_.zero_first;
        overlays_.overlays = read_overlays(m_.initial, for_overlays);
        rule_.chemicals = m_.chemicals;
        rule_.float64 = m_.float64;
        if (!m_.kernel.empty()) {
            rule_.text = m_.kernel;
        } else {
            rule_.text = sim::kernel::mesh_formula_kernel(m_.formula, m_.chemicals, m_.float64, m_.parameters);
            formula_line_ = 1;
            for (std::size_t at = 0; at < rule_.text.size() && rule_.text.compare(at, 16, "// the formula:\n") != 0; ++at)
                if (rule_.text[at] == '\n') ++formula_line_;
            ++formula_line_;
        }
        // compiled once here: a kernel figgen cannot run is refused before anything runs
        try {
            operations_ = sim::kernel::mesh_kernel_operations(rule_, cells(), neighbours_.max_neighbors);
        } catch (const sim::kernel::KernelError& e) {
            if (!m_.kernel.empty()) throw SettingError("params.kernel", "...", e.what());
            throw SettingError("params.formula", "...", said_of_formula(e.what(), formula_line_));
        }
    }

    std::vector<MemoryNeed> memory() const override {
        const mesh::Mesh& mm = cells_mesh_;
        const double n = static_cast<double>(cells()), chemicals = m_.chemicals;
        const double panels = static_cast<double>(d_.panels.size()) + 1;
        const double triangles = static_cast<double>(mm.point_ids.size() + mm.faces.size());
        return {grid_need("the mesh", 1, static_cast<double>(mm.points.size() * 8 + mm.point_ids.size() * 8 +
                                                             mm.faces.size() * 8 + mm.offsets.size() * 8),
                          1, 1),
                grid_need("the stored chemicals", chemicals, n, 8, 1),
                grid_need("the neighbour lists", n, neighbours_.max_neighbors, 8, 2),
                grid_need("the kernel's buffers", 1,
                          static_cast<double>(sim::kernel::mesh_run_bytes(
                              sim::kernel::MeshRule{rule_.text, m_.chemicals, m_.float64}, cells(), neighbours_.max_neighbors)),
                          1, 1),
                grid_need("the panels' values", panels, n, 8, 1),
                grid_need("the facets drawn", panels, triangles, sizeof(render::Facet) + 3 * 40.0, 1)};
    }

    void render(Output& out) const override {
        StepRunner run(d_, options_, out);
        sim::kernel::MeshRun model(rule_, cells(), neighbours_.max_neighbors, neighbours_.indices, neighbours_.weights,
                                   start());
        const int shown = s_.chemicals.shown.front();
        std::vector<double> now = model.chemical(shown);
        std::vector<std::pair<int, std::vector<double>>> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        const Geometry geometry = geometry_of(cells_mesh_);
        run.run({
            .check = {},
            .panel =
                [&](int step) {
                    panels.emplace_back(step, now);
                    nlohmann::json stats = nlohmann::json::object();
                    std::vector<double> all;
                    for (int c = 0; c < m_.chemicals; ++c) {
                        const std::vector<double> v = model.chemical(c);
                        stats[formula::chemical_name(c)] = statistics(v);
                        all.insert(all.end(), v.begin(), v.end());
                    }
                    panel_meta.push_back({{"step", step}, {"statistics", stats}, {"state_sha256", state_hash(all)}});
                },
            .frame =
                [&](int step) -> FrameDrawing {
                    auto values = std::make_shared<const std::vector<double>>(now);
                    const Range range = range_of({{step, *values}});
                    return {[this, values, step, range, &geometry](render::Surface& s) {
                                s.background({1, 1, 1, 1});
                                const float sc = static_cast<float>(options_.scale);
                                render::Font font(16 * sc);
                                render::Text text;
                                const float band = 30 * sc;
                                text.add(font, format_step(d_.panel_title, step), {float(s.width()) / 2, band / 2},
                                         {0, 0, 0, 1}, render::Align::centre, render::Baseline::middle);
                                draw_cells(s, {0, band, float(s.width()), float(s.height()) - band}, geometry, *values, range);
                                text.draw(s);
                            },
                            4, look_ != Look::tiling};
                },
            .advance = {},
            .leap =
                [&](int steps) {
                    try {
                        model.step(steps, 0);
                    } catch (const sim::kernel::KernelError& e) {
                        throw formula::Unstable(m_.kernel.empty() ? said_of_formula(e.what(), formula_line_) : e.what());
                    }
                    now = model.chemical(shown);
                },
        });
        const Range range = range_of(panels);
        nlohmann::json meta = {{"params", params_.used()},
                               {"style", style_.used()},
                               {"panels", panel_meta},
                               {"mesh",
                                {{"cells", cells()},
                                 {"points", cells_mesh_.point_count()},
                                 {"drawn_as", look_name(look_)},
                                 {"max_neighbors", neighbours_.max_neighbors}}},
                               {"range", {range.low, range.high}},
                               {"model_operations", operations_}};
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        FigureDrawing figure{width, height, look_ != Look::tiling, [this, &panels, range, &geometry](render::Surface& s) {
                                 draw_figure(s, panels, range, geometry);
                             }};
        figure.ready_state = [this, &model, range] { return ready_state(model, range); };
        if (look_ != Look::tiling) meta["mesh"]["view"] = {{"azimuth", azimuth_}, {"elevation", elevation_}};
        run.write_figure(figure, meta);
    }

private:
    long long cells() const { return static_cast<long long>(cells_mesh_.cell_count()); }

    // The cells the run starts from: the stored ones, then the overlays
    // (if any), each cell sampled at the mean of its points from the
    // mesh's least corner, with the description's seed.
    std::vector<std::vector<double>> start() const {
        const description::StoredMesh& stored = *mesh_;
        std::vector<std::vector<double>> cells_now = stored.chemicals;
        if (overlays_.overlays.empty()) return cells_now;
        const mesh::Mesh& m = cells_mesh_;
        std::array<double, 3> lo{}, hi{};
        for (int k = 0; k < 3; ++k) lo[k] = std::numeric_limits<double>::infinity(), hi[k] = -lo[k];
        for (std::size_t p = 0; p < m.point_count(); ++p)
            for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], m.points[3 * p + k]), hi[k] = std::max(hi[k], m.points[3 * p + k]);
        std::vector<std::array<double, 3>> centres(m.cell_count());
        for (std::size_t c = 0; c < m.cell_count(); ++c) {
            std::array<double, 3> sum{};
            const std::int64_t first = m.offsets[c], count = m.offsets[c + 1] - first;
            for (std::int64_t k = first; k < first + count; ++k)
                for (int a = 0; a < 3; ++a) sum[a] += m.points[3 * m.point_ids[static_cast<std::size_t>(k)] + a] - lo[a];
            for (int a = 0; a < 3; ++a) centres[c][a] = sum[a] / double(std::max<std::int64_t>(1, count));
        }
        sim::Random rng(d_.seed);
        formula::apply_pattern_to_cells(overlays_, cells_now, centres, {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]},
                                        m_.parameters, m_.float64, rng);
        return cells_now;
    }

    MeshModel read_model(const Description& d) {
        MeshModel m = model_schema.read(params_);
        mesh_ = d.stored_mesh;
        if (!mesh_ && m.mesh.empty())
            throw SettingError("params.mesh", "", "one of figgen's meshes (" + catalog_meshes_said() +
                                                  "), or render a Ready mesh pattern as it is (figgen render P.vtu)");
        if (mesh_ && !m.mesh.empty())
            params_.refuse("mesh", "none: the pattern file rendered is the mesh");
        if (!mesh_) mesh_ = catalog_mesh(m.mesh);
        const std::vector<Key> own = model_schema.keys();
        for (const auto& [key, value] : d.params) {
            const std::string name(key.str());
            if (is_key(own, name)) continue;
            const double v = params_.number_in(name, 0, -1e30, 1e30);
            if (!m.kernel.empty()) params_.refuse(name, "no parameter: a kernel rule's numbers are in its kernel");
            if (const auto clash = formula::parameter_name_clash(name, m.chemicals))
                params_.refuse(name, "its name is " + *clash + "; " + formula::parameter_name_allowed);
            m.parameters.emplace_back(name, v);
        }
        if (m.kernel.empty()) {
            bool timestep = false;
            for (const auto& p : m.parameters) timestep = timestep || p.first == "timestep";
            if (!timestep) throw SettingError("params.timestep", "", "the rule's timestep: X + timestep * delta_X each step");
        }
        if (mesh_->chemical_count != m.chemicals)
            params_.refuse("chemicals", "the mesh's " + std::to_string(mesh_->chemical_count) +
                                            ", the arrays its cells hold");
        return m;
    }

    std::shared_ptr<const description::StoredMesh> catalog_mesh(const std::string& name) {
        try {
            auto found = catalog_mesh_named(name);
            if (!found) params_.refuse("mesh", "one of figgen's meshes: " + catalog_meshes_said());
            return found;
        } catch (const description::FileError& e) {
            params_.refuse("mesh", "...", e.what());
        }
    }

    // The mesh as drawn: its cells' polygons (a tiling), triangles with
    // normals at their corners (a surface), or each solid cell's faces.
    struct Geometry {
        std::vector<std::vector<glm::vec2>> polygons;           // tiling: a cell's corners
        glm::vec2 lo{0}, hi{1};                                  // tiling: the bounds
        std::vector<std::pair<int, render::Facet>> facets;       // surface, solid: (cell, facet)
    };

    Geometry geometry_of(const mesh::Mesh& m) const {
        Geometry g;
        const auto point = [&](std::int64_t p) {
            return glm::vec3(float(m.points[3 * p]), float(m.points[3 * p + 1]), float(m.points[3 * p + 2]));
        };
        const std::size_t n = m.cell_count();
        if (look_ == Look::tiling) {
            g.lo = glm::vec2(std::numeric_limits<float>::infinity());
            g.hi = -g.lo;
            for (std::size_t c = 0; c < n; ++c) {
                std::vector<glm::vec2> poly;
                for (std::int64_t k = m.offsets[c]; k < m.offsets[c + 1]; ++k) {
                    const glm::vec3 p = point(m.point_ids[static_cast<std::size_t>(k)]);
                    poly.emplace_back(p.x, p.y);
                    g.lo = glm::min(g.lo, poly.back());
                    g.hi = glm::max(g.hi, poly.back());
                }
                g.polygons.push_back(std::move(poly));
            }
            return g;
        }
        if (look_ == Look::surface) {
            // smooth shading: each point's normal the area-weighted mean of its cells'
            std::vector<glm::vec3> normal(m.point_count(), glm::vec3(0));
            for (std::size_t c = 0; c < n; ++c) {
                const std::int64_t first = m.offsets[c], count = m.offsets[c + 1] - first;
                for (std::int64_t k = 1; k + 1 < count; ++k) {
                    const std::int64_t ia = m.point_ids[static_cast<std::size_t>(first)],
                                       ib = m.point_ids[static_cast<std::size_t>(first + k)],
                                       ic = m.point_ids[static_cast<std::size_t>(first + k + 1)];
                    const glm::vec3 w = glm::cross(point(ib) - point(ia), point(ic) - point(ia));
                    normal[static_cast<std::size_t>(ia)] += w;
                    normal[static_cast<std::size_t>(ib)] += w;
                    normal[static_cast<std::size_t>(ic)] += w;
                }
            }
            for (glm::vec3& v : normal)
                if (glm::length(v) > 0) v = glm::normalize(v);
            for (std::size_t c = 0; c < n; ++c) {
                const std::int64_t first = m.offsets[c], count = m.offsets[c + 1] - first;
                for (std::int64_t k = 1; k + 1 < count; ++k) {
                    const std::int64_t ia = m.point_ids[static_cast<std::size_t>(first)],
                                       ib = m.point_ids[static_cast<std::size_t>(first + k)],
                                       ic = m.point_ids[static_cast<std::size_t>(first + k + 1)];
                    render::Facet f;
                    f.a = point(ia), f.b = point(ib), f.c = point(ic);
                    f.na = normal[static_cast<std::size_t>(ia)], f.nb = normal[static_cast<std::size_t>(ib)],
                    f.nc = normal[static_cast<std::size_t>(ic)];
                    g.facets.emplace_back(static_cast<int>(c), f);
                }
            }
            return g;
        }
        // solid: a polyhedron's faces as VTK holds them, each a fan; flat shading
        if (!m.face_offsets.empty()) {
            std::int64_t at = 0;
            for (std::size_t c = 0; c < n; ++c) {
                if (m.face_offsets[c] < 0) continue;
                const std::int64_t faces = m.faces[static_cast<std::size_t>(at++)];
                for (std::int64_t f = 0; f < faces; ++f) {
                    const std::int64_t count = m.faces[static_cast<std::size_t>(at)];
                    for (std::int64_t k = 1; k + 1 < count; ++k) {
                        render::Facet facet;
                        facet.a = point(m.faces[static_cast<std::size_t>(at + 1)]);
                        facet.b = point(m.faces[static_cast<std::size_t>(at + 1 + k)]);
                        facet.c = point(m.faces[static_cast<std::size_t>(at + 2 + k)]);
                        g.facets.emplace_back(static_cast<int>(c), facet);
                    }
                    at += count + 1;
                }
            }
        }
        return g;
    }

    struct Range {
        double low = 0, high = 1;
    };
    // The drawn range: the style's, or else the least and most of every
    // panel's values, so that one colour bar serves them all.
    Range range_of(const std::vector<std::pair<int, std::vector<double>>>& panels) const {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const auto& p : panels)
            for (double v : p.second) lo = std::min(lo, v), hi = std::max(hi, v);
        Range r{spec_.vmin.value_or(lo), spec_.vmax.value_or(hi)};
        if (!std::isfinite(r.low) || !std::isfinite(r.high)) r = {0, 1};
        if (!(r.high > r.low)) r.high = r.low + 1;
        return r;
    }

    glm::vec4 colour(double v, const Range& r) const {
        const glm::vec3 c = spec_.colormap.at((v - r.low) / (r.high - r.low));
        return {c, 1};
    }

    void draw_cells(render::Surface& s, const render::Rect& view, const Geometry& g, const std::vector<double>& values,
                    const Range& range) const {
        const float sc = static_cast<float>(options_.scale);
        if (look_ == Look::tiling) {
            const glm::vec2 size = g.hi - g.lo;
            const float fit = std::min(view.w / std::max(size.x, 1e-9f), view.h / std::max(size.y, 1e-9f)) * 0.96f;
            const glm::vec2 centre = {view.x + view.w / 2, view.y + view.h / 2}, mid = (g.lo + g.hi) * 0.5f;
            const auto place = [&](glm::vec2 p) { return glm::vec2(centre.x + (p.x - mid.x) * fit, centre.y - (p.y - mid.y) * fit); };
            render::Shapes fills, edges;
            std::vector<glm::vec2> corners;
            for (std::size_t c = 0; c < g.polygons.size(); ++c) {
                corners.clear();
                for (glm::vec2 p : g.polygons[c]) corners.push_back(place(p));
                fills.convex_polygon(corners, colour(values[c], range));
                // an edge under half a pixel would be a tint, not a line, and rasterise
                // unlike its vector twin: left out
                if (s_.edge_width * sc >= 0.5) {
                    corners.push_back(corners.front());
                    edges.polyline(corners, float(s_.edge_width) * sc, {0.15f, 0.15f, 0.15f, 1});
                }
            }
            s.shapes(fills, render::Coverage::each);
            s.shapes(edges, render::Coverage::each);
            return;
        }
        std::vector<render::Facet> facets;
        const double middle = (range.low + range.high) / 2;
        for (const auto& [cell, f] : g.facets) {
            const double v = values[static_cast<std::size_t>(cell)];
            if (look_ == Look::solid && v < middle) continue;  // a lattice shows its occupied cells
            render::Facet drawn = f;
            drawn.colour = colour(v, range);
            facets.push_back(drawn);
        }
        std::vector<render::Ball> balls;
        for (const auto& [cell, f] : g.facets)
            for (glm::vec3 p : {f.a, f.b, f.c}) balls.push_back({p, 0});
        // A lattice's box, thin and grey (Ready's bounding box): where its live cells are within it.
        std::vector<render::Tube> box;
        if (look_ == Look::solid && !balls.empty()) {
            glm::vec3 lo = balls.front().centre, hi = lo;
            for (const render::Ball& b : balls) lo = glm::min(lo, b.centre), hi = glm::max(hi, b.centre);
            box = render::box_edges(lo, hi, 0.003f * glm::length(hi - lo), {0.55f, 0.55f, 0.55f, 1});
            for (const render::Tube& t : box) balls.push_back({t.a, t.radius_a});  // its corners framed too
        }
        render::Camera camera = render::frame_balls(balls, float(azimuth_), float(elevation_), view.w / view.h);
        const glm::vec3 back = glm::normalize(camera.eye - camera.target);
        const glm::vec3 left = glm::normalize(glm::cross(back, camera.up));
        render::Light light;
        light.direction = 0.8f * back + 0.5f * camera.up + 0.3f * left;
        render::draw_tubes(s, view, box, facets, camera, light, 8);
    }

    void draw_figure(render::Surface& s, const std::vector<std::pair<int, std::vector<double>>>& panels,
                     const Range& range, const Geometry& g) const {
        s.background({1, 1, 1, 1});
        const float sc = static_cast<float>(options_.scale);
        render::PlotStyle style;
        style.scale = sc;
        const render::ColourBar bar{spec_.colormap, range.low, range.high, formula::chemical_name(s_.chemicals.shown.front())};
        const float band = 36 * sc, height = float(s.height()) - band - 12 * sc;
        const float room = render::colour_bar_room(bar, height, height, style) + 12 * sc;
        const float each = (float(s.width()) - room) / float(std::max<std::size_t>(1, panels.size()));
        render::Font font(16 * sc);
        render::Text text;
        render::Rect last{};
        for (std::size_t k = 0; k < panels.size(); ++k) {
            const render::Rect view{float(k) * each, band, each, height};
            draw_cells(s, view, g, panels[k].second, range);
            text.add(font, format_step(d_.panel_title, panels[k].first), {view.x + view.w / 2, band / 2}, {0, 0, 0, 1},
                     render::Align::centre, render::Baseline::middle);
            last = view;
        }
        text.draw(s);
        render::draw_colour_bar(s, {last.x + last.w - 4 * sc, band + height * 0.1f, 4 * sc, height * 0.8f}, bar, style);
    }

    // The run's last step and its rule, for Ready's own file (--format vtu).
    ready::ReadyState ready_state(const sim::kernel::MeshRun& model, const Range& range) const {
        ready::ReadyState s;
        s.rule_name = d_.title;
        s.description = d_.caption;
        s.formula = m_.formula;
        s.kernel = m_.kernel;
        s.parameters = m_.parameters;
        s.active_chemical = formula::chemical_name(s_.chemicals.shown.front());
        s.low = range.low;
        s.high = range.high;
        s.float64 = m_.float64;
        for (int c = 0; c < m_.chemicals; ++c) s.chemicals.push_back(model.chemical(c));
        s.mesh = &cells_mesh_;
        s.points_float64 = mesh_->points_float64;
        static const char* kinds[] = {"vertex", "edge", "face"};
        s.neighborhood = kinds[static_cast<int>(m_.neighbourhood)];
        return s;
    }

    nlohmann::json statistics(const std::vector<double>& v) const {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0;
        for (double x : v) lo = std::min(lo, x), hi = std::max(hi, x), sum += x;
        return {{"min", lo}, {"max", hi}, {"mean", v.empty() ? 0.0 : sum / double(v.size())}};
    }

    std::shared_ptr<const description::StoredMesh> mesh_;  // set by read_model, before m_
    mesh::Mesh cells_mesh_;  // the same mesh as sim/mesh/ takes it
    const MeshModel m_;
    const Style s_;
    const FieldSpec spec_;
    Look look_ = Look::surface;
    double azimuth_ = 0;    // style.azimuth, or the mesh's own (default_azimuth, or 35 for a lattice)
    double elevation_ = 15;  // style.elevation, or 25 for a lattice
    mesh::Neighbours neighbours_;
    sim::kernel::MeshRule rule_;
    formula::Pattern overlays_;
    int formula_line_ = 0;
    int operations_ = 0;
};

std::unique_ptr<Scene> read_mesh(const Description& d, const SceneOptions& options) {
    return std::make_unique<MeshScene>(d, options);
}

// The most the VTU file of the last step takes: the mesh's arrays and every
// chemical's cells, 8 bytes a number at most, in base64 (zlib's blocks can
// only grow by a few bytes each), and the XML around them with the rule's
// name, description, formula or kernel and parameters.
double vtu_disk(const Description& d) {
    std::shared_ptr<const description::StoredMesh> m = d.stored_mesh;
    if (!m) {
        try {
            m = catalog_mesh_named(d.params["mesh"].value_or(std::string()));
        } catch (const description::FileError&) {
        }
    }
    if (!m) return 0;  // the scene refuses it before anything is written
    const double numbers = static_cast<double>(m->points.size() + m->point_ids.size() + m->offsets.size() +
                                               m->faces.size() + m->face_offsets.size()) +
                           static_cast<double>(m->cell_count()) * (1 + mesh_chemicals(d));
    const double texts = static_cast<double>(d.title.size() + d.caption.size() +
                                             d.params["formula"].value_or(std::string()).size() +
                                             d.params["kernel"].value_or(std::string()).size());
    return numbers * 8 * 1.34 * 1.01 + 65536 + 6 * texts + 200.0 * static_cast<double>(d.params.size());
}

}  // namespace

SceneInfo mesh_scene() {
    return {.name = "mesh", .read = read_mesh, .colormap_keys = {}, .extra_files = {{.format = "vtu", .disk = vtu_disk}}};
}

}  // namespace scenes
