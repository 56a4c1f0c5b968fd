#include "fuzz/fuzz_entries.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string_view>

#include "app/work/bounded_json.hpp"
#include "app/work/schedule.hpp"
#include "description/catalog.hpp"
#include "description/description.hpp"
#include "description/plain_name.hpp"
#include "render/layout.hpp"
#include "render/text.hpp"
#include "base/utf8.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/scene.hpp"
#include "sim/formula/run.hpp"
#include "sim/kernel/run.hpp"
#include "sim/mesh/mesh.hpp"
#include "ready/vtu.hpp"
#include "sim/lsystem.hpp"
#include "sim/snowflake.hpp"
#include "sim/turtle.hpp"

namespace fuzz {
namespace {

std::string_view text_of(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

std::vector<std::string> lines_of(std::string_view text) {
    std::vector<std::string> lines;
    while (!text.empty()) {
        const auto end = text.find('\n');
        lines.emplace_back(text.substr(0, end));
        if (end == std::string_view::npos) break;
        text.remove_prefix(end + 1);
    }
    return lines;
}

// What the output paths rely on, checked apart from is_plain_id: a bug if
// an accepted id could name anything but a plain file in the output folder.
void require_inside_output_folder(const std::string& id) {
    const bool control = std::any_of(id.begin(), id.end(), [](char c) {
        const auto b = static_cast<unsigned char>(c);
        return b < 0x20 || b == 0x7F || b >= 0x80;
    });
    if (id.empty() || id.front() == '.' || id.find('/') != std::string::npos || control ||
        std::filesystem::path(id).filename() != id || id.size() > 100)
        throw std::logic_error("an id that leaves the output folder was accepted: " + description::printable(id));
}

// What figgen prints for a refusal: one line, no control or bidirectional
// character a terminal would act on.
void require_one_clean_line(const std::string& message) {
    const std::string shown = description::printable(message);
    for (std::size_t i = 0; i < shown.size(); ++i) {
        const auto b = static_cast<unsigned char>(shown[i]);
        const bool bidi = b == 0xE2 && i + 2 < shown.size() &&
                          ((shown[i + 1] == '\x80' && (static_cast<unsigned char>(shown[i + 2]) == 0x8E ||
                                                        static_cast<unsigned char>(shown[i + 2]) == 0x8F ||
                                                        (static_cast<unsigned char>(shown[i + 2]) >= 0xAA &&
                                                         static_cast<unsigned char>(shown[i + 2]) <= 0xAE))) ||
                           (shown[i + 1] == '\x81' && static_cast<unsigned char>(shown[i + 2]) >= 0xA6 &&
                            static_cast<unsigned char>(shown[i + 2]) <= 0xA9));
        if (b < 0x20 || b == 0x7F || bidi)
            throw std::logic_error("a message would print a control or bidirectional character");
    }
}

}  // namespace

Outcome output_name(const std::uint8_t* data, std::size_t size) {
    const std::string id(text_of(data, size));
    try {
        const description::Description d =
            description::parse_description("scene = \"diffusion\"\n", "fuzz.toml", {"id=" + id});
        require_inside_output_folder(d.id);
        return Outcome::accepted;
    } catch (const description::UsageError& e) {
        require_one_clean_line(e.what());
        return Outcome::refused;
    }
}

Outcome description(const std::uint8_t* data, std::size_t size) {
    try {
        const description::Description d = description::parse_description(text_of(data, size), "fuzz.toml");
        require_inside_output_folder(d.id);
        (void)d.last_step(true);
        // The scene's phase 1: every setting read and checked, nothing run.
        description::at_source(d, [&] { return scenes::read_scene(d, scenes::SceneOptions{0.3, false}); });
        return Outcome::accepted;
    } catch (const description::UsageError& e) {
        require_one_clean_line(e.what());
        return Outcome::refused;
    }
}

Outcome set_assignments(const std::uint8_t* data, std::size_t size) {
    static const std::string base =
        "id = \"fuzz\"\nmodel = \"diffusion\"\n[params]\nn = 9\nr = 0.1\n[figure]\npanels = [0, 5]\n";
    try {
        const description::Description d = description::parse_description(base, "fuzz.toml", lines_of(text_of(data, size)));
        description::Settings params("params", d.params,
                                 {{"n", ""}, {"r", ""}, {"boundary", ""}, {"block_row", ""}, {"block_col", ""},
                                  {"block_size", ""}, {"block_value", ""}});
        (void)params.count("n", 9);
        (void)params.number("r", 0.1);
        (void)params.text("boundary", "zero");
        (void)params.integers("block_row", {});
        (void)params.numbers("block_value", {});
        (void)params.texts("block_col", {});
        (void)params.flag("block_size", false);
        return Outcome::accepted;
    } catch (const description::UsageError&) {
        return Outcome::refused;
    }
}

Outcome snowflake_rule(const std::uint8_t* data, std::size_t size) {
    sim::SnowflakeParams params;
    try {
        params.rule = sim::SnowflakeRule::parse(text_of(data, size));
    } catch (const std::invalid_argument&) {
        return Outcome::refused;
    }
    sim::Snowflake flake(params);
    for (int i = 0; i < 8; ++i) flake.step();
    (void)flake.ice_cells();
    return Outcome::accepted;
}

Outcome formula(const std::uint8_t* data, std::size_t size) {
    // The first byte picks the rule's settings (chemicals 1-3, accuracy,
    // wrap, blocks, number type, Ready's edges); the rest is the formula.
    const std::uint8_t pick = size > 0 ? data[0] : 0;
    sim::formula::Rule rule;
    rule.chemicals = 1 + pick % 3;
    rule.accuracy = static_cast<sim::formula::Accuracy>((pick / 3) % 3);
    rule.wrap = (pick & 0x10) != 0;
    rule.block_x = (pick & 0x20) ? 1 : 4;
    rule.double_precision = (pick & 0x40) != 0;
    rule.ready_edges = (pick & 0x80) == 0;
    rule.parameters = {{"timestep", 0.1}, {"k", 0.5}, {"D_a", 0.2}, {"dx", 1.0}};
    rule.code = std::string(text_of(data + (size > 0), size > 0 ? size - 1 : 0));
    std::vector<sim::Grid<double>> start;
    for (int c = 0; c < rule.chemicals; ++c) {
        sim::Grid<double> g(8, 8);
        for (int i = 0; i < 64; ++i) g.data()[i] = 0.1 * ((i * (c + 3)) % 11);
        start.push_back(std::move(g));
    }
    std::unique_ptr<sim::formula::Run> run;
    try {
        run = std::make_unique<sim::formula::Run>(rule, 8, 8, start);
    } catch (const sim::formula::FormulaError&) {
        return Outcome::refused;
    }
    // An accepted formula runs a few steps; a division by zero or a value
    // gone infinite stops it with its own error, which is no bug.
    try {
        run->step(3, 1);
    } catch (const sim::formula::Unstable&) {
    }
    for (int c = 0; c < rule.chemicals; ++c) (void)run->chemical(c);
    return Outcome::accepted;
}

Outcome lsystem(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> lines = lines_of(text_of(data, size));
    const std::string axiom = lines.empty() ? std::string() : lines.front();
    if (!lines.empty()) lines.erase(lines.begin());
    sim::LSystem system;
    try {
        system = sim::LSystem::parse(axiom, lines);
    } catch (const std::invalid_argument&) {
        return Outcome::refused;
    }
    constexpr int depth = 4;
    for (const bool article : {false, true}) {
        if (sim::segment_count(system, depth, article) > 20'000) continue;
        sim::Turtle2Params turtle;
        turtle.segment_budget = 20'000;
        (void)sim::interpret_2d(system, depth, turtle, article);
    }
    if (sim::segment_count(system, depth, false) <= 20'000 && sim::polygon_vertex_count(system, depth) <= 20'000) {
        sim::Turtle3Params turtle;
        turtle.segment_budget = 20'000;
        turtle.vertex_budget = 20'000;
        (void)sim::interpret_3d(system, depth, turtle);
    }
    return Outcome::accepted;
}

namespace {

// A figure with work items, made small, and its scene (read once).
struct WorkFigure {
    description::Description d;
    std::unique_ptr<scenes::Scene> scene;
};

const std::vector<WorkFigure>& work_figures() {
    static const std::vector<WorkFigure> all = [] {
        const std::vector<std::pair<std::string, std::vector<std::string>>> small = {
            {"tc7-phase", {"trials=10", "walk_iterations=5", "qs=[0.5, 0.6, 0.05]"}},
            {"gs-atlas", {"tiles=[3, 2]", "steps=100", "n=16"}},
            {"bd-roughness", {"widths=[20, 40]", "seeds=2"}},
            {"pc-threshold", {"sizes=[8, 16]", "samples=40", "samples_per_item=20"}},
            {"tc7-ex1", {"n=40", "gallery_steps=15"}},
        };
        std::vector<WorkFigure> figures;
        for (const auto& [id, overrides] : small) {
            WorkFigure f{description::load_description(description::resolve_figure(id), overrides), nullptr};
            f.scene = scenes::read_scene(f.d, scenes::SceneOptions{0.3, false});
            if (!f.scene->work()) throw std::logic_error(id + " has no work items");
            figures.push_back(std::move(f));
        }
        return figures;
    }();
    return all;
}

std::string without_breaking_space(const std::string& text) {
    std::string kept;
    for (const char c : text)
        if (c != ' ' && c != '\n') kept += c;
    return kept;
}

// The caption as wrapped holds the text: only spaces and line feeds may go.
void require_whole(const render::Font& font, const std::string& text, const std::vector<std::string>& lines,
                   const std::string& language) {
    std::string joined;
    for (const std::string& line : lines) joined += line;
    if (without_breaking_space(joined) != without_breaking_space(font.shape(text, language).text))
        throw std::logic_error("wrap lost or changed characters of " + description::printable_short(text));
}

}  // namespace

Outcome parts(const std::uint8_t* data, std::size_t size) {
    if (size < 3) return Outcome::refused;
    const int mode = data[0] % 3;
    const WorkFigure& figure = work_figures()[data[1] % work_figures().size()];
    const scenes::WorkItems& items = *figure.scene->work();
    const int item = data[2] % items.item_count();
    const std::string_view rest = text_of(data + 3, size - 3);
    const std::string manifest = std::string(64, '0');  // a manifest's SHA-256, as the parts hold it
    try {
        if (mode == 0) {
            // A manifest: read, then its values shown as a refusal shows them.
            const nlohmann::json m = app::json_bounded(rest);
            if (m.is_object())
                for (const auto& [key, value] : m.items()) require_one_clean_line(description::printable(value.dump(), 80));
            return Outcome::accepted;
        }
        std::string bytes(rest);
        if (mode == 2) {
            // The bytes as a result, in a part with its true hash: the scene's check decides.
            const nlohmann::json result = app::cbor_bounded(rest);
            bytes = app::part_bytes(item, result, items, manifest);
        }
        (void)app::result_of_part(bytes, item, items, manifest);
        return Outcome::accepted;
    } catch (const app::MalformedData& e) {
        require_one_clean_line(e.what());
        return Outcome::refused;
    }
}

Outcome caption_text(const std::uint8_t* data, std::size_t size) {
    if (size < 2) return Outcome::refused;
    static const char* const languages[] = {"", "ja", "zh-cn", "ko"};
    const std::string language = languages[(data[0] >> 1) & 3];
    const float room = 8.0f + 4.0f * static_cast<float>(data[1]);
    std::string text;
    if (data[0] & 1) {
        for (std::size_t i = 2; i + 4 <= size; i += 4)
            text += base::encode_utf8(static_cast<char32_t>(
                (data[i] | data[i + 1] << 8 | data[i + 2] << 16 | static_cast<std::uint32_t>(data[i + 3]) << 24) %
                0x110000u));
    } else {
        text.assign(reinterpret_cast<const char*>(data) + 2, size - 2);
    }
    render::set_missing_glyph_warning([](const std::string&) {});  // every unknown character would say so

    // As drawn, whatever the reader would say: no code point may crash it.
    const render::Font& font = render::font_of_size(15);
    const std::vector<std::string> lines = render::wrap(font, text, room, language);
    require_whole(font, text, lines, language);
    render::PageText page;
    float y = 20;
    for (const std::string& line : lines) {
        const render::LineInk ink = render::line_ink(font, line, {room / 2 + 8, y}, render::Align::centre,
                                                     render::Baseline::baseline, 0, language);
        page.texts.push_back({ink.box, "a line", -1, ink.glyphs, ink.em});
        y += font.line_height();
    }
    (void)render::text_clash(page, render::Rect{0, 0, room + 16, y});
    const render::GridText titled = render::grid_text({{10, 40, room, 60}, {room + 20, 40, 60, 60}}, {text, "b"},
                                                      render::TitlePlace::above, 15, 4);
    (void)render::text_clash(titled, render::Rect{0, 0, room + 90, 110});

    // As the description reader and the caption take it.
    try {
        const description::Description d = description::parse_description(
            "id = \"fuzz\"\nscene = \"diffusion\"\n[figure]\npanels = [0]\n", "fuzz.toml",
            {"title=" + text, "figure.caption=title"});
        const int width = static_cast<int>(room) + 16;
        const scenes::FigureCaption caption =
            description::at_source(d, [&] { return scenes::figure_caption(d, width, 16384, 1.0); });
        require_whole(font, d.title, caption.lines, "");
        return Outcome::accepted;
    } catch (const description::UsageError& e) {
        require_one_clean_line(e.what());
        // A size the refusal suggests is one figgen would take.
        // It ends the message ("--size WxH or larger fits them, ..."): the title
        // quoted before it may hold "--size " too.
        const std::string message = e.what();
        const auto larger = message.rfind(" or larger fits them");
        if (const auto at = larger == std::string::npos ? larger : message.rfind("--size ", larger);
            at != std::string::npos) {
            int w = 0, h = 0;
            if (std::sscanf(message.c_str() + at + 7, "%dx%d", &w, &h) != 2 || w > description::max_figure_side ||
                h > description::max_figure_side)
                throw std::logic_error("a refusal suggests a size figgen refuses: " + message.substr(at, 40));
        }
        return Outcome::refused;
    }
}

Outcome kernel(const std::uint8_t* data, std::size_t size) {
    // The first byte picks the run: bit 0 two chemicals, bit 1 doubles,
    // bit 2 blocks of 4, bits 3-4 the grid (16, 8 x 8, 4 x 4 x 4, a mesh
    // of 6 triangles round a point); the rest is the kernel.
    const std::uint8_t pick = size > 0 ? data[0] : 0;
    const std::string text(text_of(data + (size > 0), size > 0 ? size - 1 : 0));
    const int chemicals = 1 + (pick & 1);
    const bool float64 = (pick & 2) != 0;
    const int shape = (pick >> 3) & 3;
    try {
        if (shape == 3) {
            // six triangles round the origin, each a neighbour of the two beside it
            sim::mesh::Mesh m;
            m.points = {0, 0, 0};
            for (int k = 0; k < 6; ++k) {
                m.points.push_back(std::cos(k * M_PI / 3));
                m.points.push_back(std::sin(k * M_PI / 3));
                m.points.push_back(0);
            }
            for (int k = 0; k < 6; ++k) {
                m.point_ids.insert(m.point_ids.end(), {0, 1 + k, 1 + (k + 1) % 6});
                m.offsets.push_back(static_cast<std::int64_t>(m.point_ids.size()));
                m.types.push_back(sim::mesh::cell_type::triangle);
            }
            const sim::mesh::Neighbours n = sim::mesh::neighbours(m, sim::mesh::Kind::edge);
            sim::kernel::MeshRule rule{text, chemicals, float64, 1 << 12};
            std::vector<std::vector<double>> start(static_cast<std::size_t>(chemicals), {0.1, 0.5, 0.9, 0.3, 0.7, 0.2});
            sim::kernel::MeshRun run(rule, 6, n.max_neighbors, n.indices, n.weights, start);
            try {
                run.step(2, 1);
            } catch (const sim::kernel::KernelError&) {
            }
            (void)run.chemical(0);
            return Outcome::accepted;
        }
        sim::kernel::ImageRule rule;
        rule.text = text;
        rule.chemicals = chemicals;
        rule.float64 = float64;
        rule.block[0] = (pick & 4) ? 4 : 1;
        rule.trip_budget = 1 << 12;
        const int w = shape == 0 ? 16 : shape == 1 ? 8 : 4, h = shape == 0 ? 1 : shape == 1 ? 8 : 4, d = shape == 2 ? 4 : 1;
        std::vector<sim::Grid<double>> start;
        for (int c = 0; c < chemicals; ++c) {
            sim::Grid<double> g(h * d, w);
            for (std::size_t i = 0; i < g.size(); ++i) g.data()[i] = 0.1 * static_cast<double>((i * static_cast<std::size_t>(c + 3)) % 11);
            start.push_back(std::move(g));
        }
        sim::kernel::ImageRun run(rule, w, h, d, start);
        // a fault of the run (an index out of range, a division by zero, a
        // number gone infinite) stops it with its own error: no bug
        try {
            run.step(2, 1 + (pick >> 5) % 2);
        } catch (const sim::kernel::KernelError&) {
        }
        for (int c = 0; c < chemicals; ++c) (void)run.chemical(c);
    } catch (const sim::kernel::KernelError&) {
        return Outcome::refused;
    }
    return Outcome::accepted;
}

Outcome mesh(const std::uint8_t* data, std::size_t size) {
    try {
        const ready::vtu::UnstructuredGrid g = ready::vtu::read_vtu(text_of(data, size));
        // what a read mesh is used for: its neighbours by each kind, and back out
        for (const sim::mesh::Kind kind : {sim::mesh::Kind::vertex, sim::mesh::Kind::edge, sim::mesh::Kind::face}) {
            try {
                (void)sim::mesh::neighbours(g.mesh, kind);
            } catch (const std::invalid_argument&) {
                return Outcome::refused;  // mixed cell types: Ready refuses them too
            }
        }
        // Written out, it reads back as the same mesh and the same values, bit for bit.
        const ready::vtu::UnstructuredGrid back = ready::vtu::read_vtu(ready::vtu::write_vtu(g));
        const auto same_bits = [](const std::vector<double>& x, const std::vector<double>& y) {
            return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0);
        };
        bool same = same_bits(back.mesh.points, g.mesh.points) && back.mesh.offsets == g.mesh.offsets &&
                    back.mesh.point_ids == g.mesh.point_ids && back.mesh.types == g.mesh.types &&
                    back.mesh.faces == g.mesh.faces && back.cell_data.size() == g.cell_data.size();
        for (std::size_t i = 0; same && i < g.cell_data.size(); ++i)
            same = back.cell_data[i].name == g.cell_data[i].name &&
                   back.cell_data[i].components == g.cell_data[i].components &&
                   same_bits(back.cell_data[i].values, g.cell_data[i].values);
        if (!same) throw std::logic_error("a mesh written back by write_vtu reads as another");
    } catch (const ready::vtu::DataError&) {
        return Outcome::refused;
    }
    return Outcome::accepted;
}

const std::vector<Target>& targets() {
    static const std::vector<Target> all = {
        {"description", description},
        {"set", set_assignments},
        {"snowflake_rule", snowflake_rule},
        {"lsystem", lsystem},
        {"formula", formula},
        {"output_name", output_name},
        {"parts", parts},
        {"caption_text", caption_text},
        {"vtk_arrays", vtk_arrays},
        {"ready_pattern", ready_pattern},
        {"kernel", kernel},
        {"mesh", mesh},
    };
    return all;
}

}  // namespace fuzz
