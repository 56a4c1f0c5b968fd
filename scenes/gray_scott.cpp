// Gray-Scott reaction-diffusion (Think Complexity 2e, Figs 7.2-7.4): drawn as
// the book draws it, A through Reds and B through Blues, each autoscaled to
// its own range, stacked at alpha 0.7 with bicubic-like smoothing.
#include "sim/gray_scott.hpp"

#include "base/digest.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"
#include "sim/gray_scott_kernels.hpp"
#include "sim/random.hpp"

namespace scenes {
namespace {

using P = sim::GrayScottParams;
const Schema<P> param_schema = Schema<P>()
                                   .count("n", &P::n, "grid size in cells")
                                   .number("ra", &P::ra, "diffusion rate of A")
                                   .number("rb", &P::rb, "diffusion rate of B")
                                   .number("f", &P::f, "feed rate")
                                   .number("k", &P::k, "kill rate")
                                   .number("noise", &P::noise, "B starts uniform in [0, noise)")
                                   .number("island", &P::island, "added to B on the central square of side 2*(n/20)")
                                   .check(validated<P>());

// A through Reds and B through Blues.
struct Style {
    FieldSpec a{render::colormap("Reds"), {}, {}, 0.7f, render::Sampling::smooth};
    FieldSpec b{render::colormap("Blues"), {}, {}, 0.7f, render::Sampling::smooth};
};
const Schema<Style> style_schema =
    Schema<Style>().part(field_spec_schema(), &Style::a, "a_").part(field_spec_schema(), &Style::b, "b_");

// The run on the fast double kernel (sim/gray_scott_kernels.hpp), which
// equals sim::GrayScott bit for bit on any number of threads: it leaps from
// one step an output needs to the next, and a() and b() are the fields there.
class KernelRun {
public:
    KernelRun(const sim::GrayScottParams& p, sim::Random& rng) : KernelRun(sim::GrayScott(p, rng)) {}

    const sim::Grid<double>& a() const { return a_; }
    const sim::Grid<double>& b() const { return b_; }

    // Concentrations live in [0, 1]; beyond 10 the run has blown up. The
    // runner checks the fields at every step it stops at; if they went bad
    // during the leap there, the leap is stepped again one step at a time on
    // the model, from the sound fields it started from, to name the first
    // step that was bad (the same bits, so the same step).
    void check(int step) const {
        try {
            require_fields(a_, b_, step);
        } catch (const std::runtime_error&) {
            if (sound_step_ >= 0) {
                sim::GrayScott model(kernel_.params(), sound_a_, sound_b_);
                for (int s = sound_step_ + 1; s <= step; ++s) {
                    model.step();
                    require_fields(model.a(), model.b(), s);
                }
            }
            throw;
        }
    }

    // `steps` steps on the kernel; the fields it leaves are checked by check().
    void leap(int steps) {
        sound_step_ = kernel_.steps();  // the runner checked the fields here
        sound_a_ = std::move(a_);
        sound_b_ = std::move(b_);
        kernel_.step(steps, threads());
        a_ = kernel_.a();
        b_ = kernel_.b();
    }

private:
    static constexpr double bound = 10.0;
    static void require_fields(const sim::Grid<double>& a, const sim::Grid<double>& b, int step) {
        require_finite(a, "gray_scott (A)", step, bound);
        require_finite(b, "gray_scott (B)", step, bound);
    }
    // One thread below 256^2 cells, OpenMP's default above. A second thread
    // gains little on a small grid (the double kernel at n = 100: 0.75 G
    // cell-updates/s on one thread, 0.91 on two), and between leaps libgomp's
    // idle thread spins (its default wait policy) while the frame is drawn
    // and encoded: 23% of tc7-2's film's CPU time went to that spin.
    int threads() const { return kernel_.params().n < 256 ? 1 : 0; }
    explicit KernelRun(const sim::GrayScott& start)
        : kernel_(start.params(), start.a(), start.b()), a_(start.a()), b_(start.b()) {}

    sim::GrayScottKernel<double> kernel_;
    sim::Grid<double> a_, b_;
    sim::Grid<double> sound_a_, sound_b_;  // the fields before the last leap, checked sound
    int sound_step_ = -1;                  // their step; -1 before the first leap
};

// A kept panel copies the fields; a frame, drawn at once, only looks at them.
FieldPanel panel_of(const KernelRun& model, const FieldSpec& a, const FieldSpec& b, std::string title, Cells cells) {
    return {std::move(title), {field_layer(model.a(), a, cells), field_layer(model.b(), b, cells)}};
}

nlohmann::json panel_metadata(const KernelRun& model, int step) {
    auto summary = [](const sim::Grid<double>& g) {
        auto stats = field_statistics(g);
        stats.erase("sum");
        return stats;
    };
    // One hash over both fields: A's cells, then B's.
    std::vector<double> state(model.a().cells());
    state.insert(state.end(), model.b().cells().begin(), model.b().cells().end());
    return {{"step", step},
            {"statistics", {{"A", summary(model.a())}, {"B", summary(model.b())}}},
            {"state_sha256", base::sha256_hex(state.data(), state.size() * sizeof(double))}};
}

class GrayScottScene : public SceneBase {
public:
    GrayScottScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          spec_(style_schema.read(style_)) {
        if (d.panels.empty()) throw SettingError("figure.panels", "[]", "one step at least");
        require_drawable(params_, "n", "the field", p_.n, p_.n);
    }

    // The kernel's A and B and their next steps (padded), A and B where the
    // run stands, the two before a leap and the two the kernel hands back,
    // and a copy of both per panel.
    std::vector<MemoryNeed> memory() const override {
        return {grid_need("grids of doubles", p_.n + 2, p_.n + 2, 8, 10.0 + 2.0 * double(d_.panels.size())),
                grid_need("field textures", p_.n, p_.n, field_layer_bytes_per_cell, 2.0 * double(d_.panels.size()))};
    }

    void render(Output& out) const override {
        StepRunner run(d_, options_, out);
        sim::Random rng(d_.seed);
        KernelRun model(p_, rng);
        std::vector<FieldPanel> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        run.run({
            .check = [&](int step) { model.check(step); },
            .panel =
                [&](int step) {
                    panels.push_back(
                        panel_of(model, spec_.a, spec_.b, format_step(d_.panel_title, step), Cells::copied));
                    panel_meta.push_back(panel_metadata(model, step));
                },
            .frame = [&](int step) -> FrameDrawing {
                return run.field_frame(
                    {panel_of(model, spec_.a, spec_.b, format_step(d_.animation->title, step), Cells::viewed)});
            },
            .advance = {},
            .leap = [&](int steps) { model.leap(steps); },
        });
        nlohmann::json meta = {{"params", params_.used()}, {"style", style_.used()}, {"panels", panel_meta}};
        run.write_field_figure(panels, meta);
    }

private:
    const sim::GrayScottParams p_;
    const Style spec_;
};

std::unique_ptr<Scene> read_gray_scott(const Description& d, const SceneOptions& options) {
    return std::make_unique<GrayScottScene>(d, options);
}

}  // namespace

SceneInfo gray_scott_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"gray_scott",
            read_gray_scott,
            {"a_colormap", "b_colormap"},
            {
                {"/panels/*/statistics/B/mean", "mean B at step {step}", "number", ""},
                {"/panels/*/statistics/A/mean", "mean A at step {step}", "number", ""},
            }};
}

}  // namespace scenes
