#include "render/plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string_view>

#include "render/field.hpp"
#include "render/shapes.hpp"
#include "render/ticks.hpp"

namespace render {
namespace {

// matplotlib's text box around a line of DejaVu Sans, in ems: from the top
// of "l" above the baseline to the bottom of "p" below it.
constexpr float text_ascent = 0.76f;
constexpr float text_descent = 0.21f;

// Tick labels with an exponent are set as matplotlib's mathtext sets
// "10^{-3}": the exponent in ordinary digits at 0.7 of the size, raised
// 0.375 em, which reads larger and lower than the font's superscript glyphs.
constexpr float script_scale = 0.7f;
constexpr float script_rise = 0.375f;

struct TickLabel {
    std::string base, exponent;  // "10" and "−3" for "10⁻³"
};

TickLabel split_exponent(const std::string& label) {
    static const std::pair<std::string_view, const char*> superscripts[] = {
        {"\u2070", "0"}, {"\u00b9", "1"}, {"\u00b2", "2"}, {"\u00b3", "3"}, {"\u2074", "4"}, {"\u2075", "5"},
        {"\u2076", "6"}, {"\u2077", "7"}, {"\u2078", "8"}, {"\u2079", "9"}, {"\u207b", "\u2212"}};
    TickLabel out{label, ""};
    for (bool found = true; found;) {
        found = false;
        for (const auto& [glyph, plain] : superscripts)
            if (out.base.ends_with(glyph)) {
                out.base.resize(out.base.size() - glyph.size());
                out.exponent.insert(0, plain);
                found = true;
            }
    }
    return out;
}

struct TickFonts {
    Font& base;
    Font& script;
    float width(const TickLabel& l) const { return base.width(l.base) + script.width(l.exponent); }
};

// Where a plot's shapes and text go: onto a surface, or, for the fit
// check, only the text, as named boxes on a PageText. Both take the same
// positions from the same code, so the check sees what would be drawn.
class TextSink {
public:
    explicit TextSink(Surface& surface) : surface_(&surface) {}
    TextSink(PageText& page, int panel, std::string of) : page_(&page), panel_(panel), of_(std::move(of)) {}

    bool drawing() const { return surface_ != nullptr; }
    Surface* surface() const { return surface_; }
    // Adds a line (Text::add's arguments) and returns its ink.
    LineInk add(Font& font, std::string_view utf8, glm::vec2 at, const glm::vec4& colour, Align align = Align::left,
                Baseline baseline = Baseline::baseline, float rotation = 0) {
        if (drawing()) {
            text_.add(font, utf8, at, colour, align, baseline, rotation);
            return {};
        }
        return line_ink(font, utf8, at, align, baseline, rotation);
    }
    // Names a text ("the x tick label "0.5"") for the check; `inside`: it belongs inside the plot's frame.
    void name(const LineInk& ink, const std::string& what, bool inside = false) {
        if (!drawing()) page_->texts.push_back({ink.box, what + of_, inside ? panel_ : -1, ink.glyphs, ink.em});
    }
    // Names a solid box (the legend's).
    void name(const Rect& box, const std::string& what, bool inside = false) { name(LineInk{box, {}}, what, inside); }
    // Draws `shapes`, then the text added since the last flush, over them.
    void flush(const Shapes& shapes) {
        if (!drawing()) return;
        shapes.draw(*surface_);
        text_.draw(*surface_);
        text_.clear();
    }

private:
    Surface* surface_ = nullptr;
    Text text_;
    PageText* page_ = nullptr;
    int panel_ = -1;
    std::string of_;  // " of plot 2"
};

// Two lines' ink as one text's.
LineInk united(LineInk a, const LineInk& b) {
    if (a.box.w <= 0) return b;
    if (b.box.w <= 0) return a;
    const float x = std::min(a.box.x, b.box.x), y = std::min(a.box.y, b.box.y);
    a.box = {x, y, std::max(a.box.right(), b.box.right()) - x, std::max(a.box.bottom(), b.box.bottom()) - y};
    a.glyphs.insert(a.glyphs.end(), b.glyphs.begin(), b.glyphs.end());
    a.em = std::max(a.em, b.em);
    return a;
}

// Adds a tick label anchored like Text::add (Baseline::middle: the middle of
// the base's capitals), and names its box, exponent included.
void add_tick_label(TextSink& text, const TickFonts& fonts, const std::string& shown, glm::vec2 at,
                    const glm::vec4& colour, Align align, Baseline baseline, const char* axis) {
    const TickLabel label = split_exponent(shown);
    const float w = fonts.width(label);
    const float x = align == Align::left ? at.x : align == Align::centre ? at.x - w / 2 : at.x - w;
    const float y = baseline == Baseline::middle ? at.y + fonts.base.cap_height() / 2
                    : baseline == Baseline::top  ? at.y + fonts.base.ascender()
                    : baseline == Baseline::bottom ? at.y + fonts.base.descender()
                                                   : at.y;
    LineInk box = text.add(fonts.base, label.base, {x, y}, colour);
    if (!label.exponent.empty())
        box = united(box, text.add(fonts.script, label.exponent,
                                   {x + fonts.base.width(label.base), y - script_rise * fonts.base.pixel_size()},
                                   colour));
    text.name(box, std::string("the ") + axis + " tick label \"" + shown + "\"");
}

bool usable(double v, Scale scale) { return std::isfinite(v) && (scale == Scale::linear || v > 0); }

// Data to pixels along one axis.
struct AxisMap {
    Scale scale;
    double lo, hi;      // the view limits, data units
    double p_lo, p_hi;  // where they land, pixels
    double t(double v) const { return scale == Scale::log ? std::log10(v) : v; }
    double operator()(double v) const { return p_lo + (t(v) - t(lo)) / (t(hi) - t(lo)) * (p_hi - p_lo); }
};

// The view limits of one axis: the caller's, or the data's with margins.
std::pair<double, double> view_range(const Axes& axes, bool x_axis) {
    const Scale scale = x_axis ? axes.x_scale : axes.y_scale;
    const auto& given = x_axis ? axes.x_range : axes.y_range;
    const char* name = x_axis ? "x" : "y";
    if (given) {
        auto [lo, hi] = *given;
        if (!usable(lo, scale) || !usable(hi, scale))
            throw std::invalid_argument(std::string("draw_axes: the ") + name + " range must be finite" +
                                        (scale == Scale::log ? " and positive on a log axis" : ""));
        if (lo == hi) return scale == Scale::log ? log_auto_range(lo, hi) : linear_auto_range(lo, hi);
        return {lo, hi};
    }
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Series& s : axes.series)
        for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
            if (!usable(s.x[i], axes.x_scale) || !usable(s.y[i], axes.y_scale)) continue;
            const double v = x_axis ? s.x[i] : s.y[i];
            lo = std::min(lo, v), hi = std::max(hi, v);
        }
    for (const ReferenceLine& r : axes.reference_lines)
        if ((r.direction == Direction::vertical) == x_axis && usable(r.at, scale))
            lo = std::min(lo, r.at), hi = std::max(hi, r.at);
    if (lo > hi) return scale == Scale::log ? std::pair{1.0, 10.0} : std::pair{0.0, 1.0};  // nothing to show
    return scale == Scale::log ? log_auto_range(lo, hi) : linear_auto_range(lo, hi);
}

AxisTicks ticks_of(const AxisMap& map, float length, float font_size, bool horizontal) {
    const int bins = tick_bins(length, font_size, horizontal);
    return map.scale == Scale::log ? log_ticks(map.lo, map.hi, bins) : linear_ticks(map.lo, map.hi, bins);
}

// The centre of a line `width` pixels wide nearest to v that keeps its edges
// on pixel edges, as matplotlib snaps spines and ticks: crisp, not smeared
// over two half-covered pixels.
float snap(float v, float width) {
    const int pixels = std::max(1, int(std::lround(width)));
    return pixels % 2 == 1 ? std::floor(v) + 0.5f : std::round(v);
}

// The stretches of a pixel-space path inside `box`, each with the arc length
// at which it starts, so that a dash pattern runs on across the cuts.
struct Run {
    std::vector<glm::vec2> points;
    float start = 0;
};

std::vector<Run> clip_path(const std::vector<glm::dvec2>& path, const Rect& box) {
    std::vector<Run> runs;
    Run run;
    auto finish = [&] {
        if (run.points.size() >= 2) runs.push_back(run);
        run.points.clear();
    };
    double arc = 0;
    for (std::size_t i = 1; i < path.size(); ++i) {
        const glm::dvec2 a = path[i - 1], d = path[i] - a;
        const double length = glm::length(d);
        // Liang-Barsky: the part t0..t1 of the segment inside the box.
        double t0 = 0, t1 = 1;
        const double p[4] = {-d.x, d.x, -d.y, d.y};
        const double q[4] = {a.x - box.x, box.right() - a.x, a.y - box.y, box.bottom() - a.y};
        bool inside = true;
        for (int k = 0; k < 4 && inside; ++k) {
            if (p[k] == 0) {
                inside = q[k] >= 0;
            } else {
                const double r = q[k] / p[k];
                if (p[k] < 0) t0 = std::max(t0, r);
                else t1 = std::min(t1, r);
                inside = t0 <= t1;
            }
        }
        if (!inside) {
            finish();
        } else {
            if (t0 > 0 || run.points.empty()) {
                finish();
                run.start = float(arc + t0 * length);
                run.points.push_back(glm::vec2(a + t0 * d));
            }
            run.points.push_back(glm::vec2(a + t1 * d));
            if (t1 < 1) finish();
        }
        arc += length;
    }
    finish();
    return runs;
}

std::vector<float> scaled(const std::vector<float>& dash, float scale) {
    std::vector<float> out;
    for (float d : dash) out.push_back(d * scale);
    return out;
}

// A line through pixel-space points (NaN: a gap), cut to `box`.
void add_line(Shapes& shapes, const std::vector<glm::dvec2>& points, const Rect& box, const glm::vec4& colour,
              float width, const std::vector<float>& dash) {
    const LineCap cap = dash.empty() ? LineCap::square : LineCap::butt;  // matplotlib's solid and dash cap styles
    std::vector<glm::dvec2> piece;
    auto flush = [&] {
        for (const Run& run : clip_path(piece, box)) shapes.polyline(run.points, width, colour, dash, run.start, cap);
        piece.clear();
    };
    for (const glm::dvec2& p : points) {
        if (std::isnan(p.x)) flush();
        else piece.push_back(p);
    }
    flush();
}

// matplotlib's "o" marker: a disc, and a rim in the same colour centred on its edge.
void add_marker(Shapes& shapes, glm::vec2 at, float radius, float rim, const glm::vec4& colour) {
    shapes.disc(at, radius, colour);
    shapes.ring(at, radius - rim / 2, radius + rim / 2, colour);
}

// Lines and markers of the data and the reference lines. The frame cuts
// them with a clip to whole pixels: that is matplotlib's clip box exactly,
// pixel for pixel, and it cuts thick lines, dash ends and markers at the
// spine with no geometry to work out. Each line is drawn with
// Coverage::once: where a translucent line overlaps itself (joints of short
// segments, crossings) it keeps one shade, as matplotlib fills a whole
// stroke in one pass. Segments are also clipped in double precision to
// a box a little larger than the frame, so that far-off data never reaches
// the rasteriser as huge coordinates and dashes are only made where seen.
void draw_data(Surface& surface, const Rect& frame, const Axes& axes, const AxisMap& mx, const AxisMap& my,
               const PlotStyle& style) {
    const float scale = style.scale, rim = style.marker_edge * scale;
    surface.clip(frame);
    const float slack = 16 * scale;
    for (const ReferenceLine& r : axes.reference_lines) {
        const float width = r.line_width * scale;
        const Rect box{frame.x - slack - width, frame.y - slack - width, frame.w + 2 * (slack + width),
                       frame.h + 2 * (slack + width)};
        const bool horizontal = r.direction == Direction::horizontal;
        if (!usable(r.at, horizontal ? my.scale : mx.scale) || !(width > 0)) continue;
        const double v = horizontal ? my(r.at) : mx(r.at);
        const std::vector<glm::dvec2> ends =
            horizontal ? std::vector<glm::dvec2>{{frame.x, v}, {frame.right(), v}}
                       : std::vector<glm::dvec2>{{v, frame.bottom()}, {v, frame.y}};
        Shapes line;
        add_line(line, ends, box, r.colour, width, scaled(r.dash, scale));
        if (!line.empty()) surface.shapes(line, Coverage::once);
    }
    for (const Series& s : axes.series) {
        const float width = s.line_width * scale, radius = s.marker_size * scale / 2;
        const float reach = slack + std::max(width, radius + rim);
        const Rect box{frame.x - reach, frame.y - reach, frame.w + 2 * reach, frame.h + 2 * reach};
        std::vector<glm::dvec2> points;
        for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
            const bool ok = usable(s.x[i], mx.scale) && usable(s.y[i], my.scale);
            const double nan = std::numeric_limits<double>::quiet_NaN();
            points.push_back(ok ? glm::dvec2{mx(s.x[i]), my(s.y[i])} : glm::dvec2{nan, nan});
        }
        Shapes line, markers;
        if (width > 0) add_line(line, points, box, s.colour, width, scaled(s.dash, scale));
        if (radius > 0)  // each marker on its own, as matplotlib draws them: overlapping ones darken
            for (const glm::dvec2& p : points)
                if (p.x >= box.x && p.x <= box.right() && p.y >= box.y && p.y <= box.bottom())
                    add_marker(markers, glm::vec2(p), radius, rim, s.colour);
        if (!line.empty()) surface.shapes(line, Coverage::once);
        markers.draw(surface);
    }
    surface.unclip();
}

// Spines, ticks, tick labels, axis labels, title and notes.
void draw_decorations(TextSink& text, const Rect& frame, const Axes& axes, const AxisMap& mx,
                      const AxisMap& my, const PlotStyle& st) {
    const float s = st.scale;
    Font& tick_font = font_of_size(st.font_size * s);
    Font& label_font = font_of_size(st.label_size * s);
    Shapes shapes;
    const float sw = st.spine_width * s;
    const float left = snap(frame.x, sw), right = snap(frame.right(), sw);
    const float top = snap(frame.y, sw), bottom = snap(frame.bottom(), sw);
    shapes.rect({left - sw / 2, top - sw / 2, sw, bottom - top + sw}, st.ink);
    shapes.rect({right - sw / 2, top - sw / 2, sw, bottom - top + sw}, st.ink);
    shapes.rect({left - sw / 2, top - sw / 2, right - left + sw, sw}, st.ink);
    shapes.rect({left - sw / 2, bottom - sw / 2, right - left + sw, sw}, st.ink);

    const float major = st.major_tick * s, pad = st.tick_pad * s;
    const AxisTicks xt = ticks_of(mx, frame.w, tick_font.pixel_size(), true);
    const AxisTicks yt = ticks_of(my, frame.h, tick_font.pixel_size(), false);
    auto x_ticks = [&](const std::vector<Tick>& ticks, float length, float width) {
        for (const Tick& t : ticks) {
            const float x = snap(float(mx(t.value)), width);
            shapes.rect({x - width / 2, bottom, width, length}, st.ink);
        }
    };
    auto y_ticks = [&](const std::vector<Tick>& ticks, float length, float width) {
        for (const Tick& t : ticks) {
            const float y = snap(float(my(t.value)), width);
            shapes.rect({left - length, y - width / 2, length, width}, st.ink);
        }
    };
    x_ticks(xt.major, major, st.major_tick_width * s);
    x_ticks(xt.minor, st.minor_tick * s, st.minor_tick_width * s);
    y_ticks(yt.major, major, st.major_tick_width * s);
    y_ticks(yt.minor, st.minor_tick * s, st.minor_tick_width * s);

    // Tick labels: below the x ticks, the tops of their digits `pad` under
    // the ticks' ends; left of the y ticks, centred on them.
    const TickFonts fonts{tick_font, font_of_size(script_scale * tick_font.pixel_size())};
    const float x_baseline = bottom + major + pad + tick_font.cap_height();
    float labels_left = left - major - pad;
    for (const auto* list : {&xt.major, &xt.minor})
        for (const Tick& t : *list)
            if (!t.label.empty())
                add_tick_label(text, fonts, t.label, {float(mx(t.value)), x_baseline}, st.ink,
                               Align::centre, Baseline::baseline, "x");
    for (const auto* list : {&yt.major, &yt.minor})
        for (const Tick& t : *list)
            if (!t.label.empty()) {
                const TickLabel label = split_exponent(t.label);
                add_tick_label(text, fonts, t.label, {left - major - pad, float(my(t.value))}, st.ink, Align::right,
                               Baseline::middle, "y");
                labels_left = std::min(labels_left, left - major - pad - fonts.width(label));
            }

    const float lf = label_font.pixel_size();
    if (!axes.x_label.empty()) {
        const float y = x_baseline + text_descent * tick_font.pixel_size() + st.label_pad * s + text_ascent * lf;
        text.name(text.add(label_font, axes.x_label, {frame.x + frame.w / 2, y}, st.ink, Align::centre),
                  "the x axis label");
    }
    if (!axes.y_label.empty()) {  // turned to read upwards, its text box's bottom label_pad left of the labels
        const float x = labels_left - st.label_pad * s - text_descent * lf;
        text.name(
            text.add(label_font, axes.y_label, {x, frame.y + frame.h / 2}, st.ink, Align::centre, Baseline::baseline, 90),
            "the y axis label");
    }
    if (!axes.title.empty())
        text.name(text.add(font_of_size(st.title_size * s), axes.title,
                           {frame.x + frame.w / 2, frame.y - st.title_pad * s}, st.ink, Align::centre),
                  "the title");
    for (const Note& n : axes.notes)
        text.name(text.add(tick_font, n.text, {frame.x + n.at.x * frame.w, frame.bottom() - n.at.y * frame.h},
                           n.colour, n.align),
                  "the note \"" + n.text + "\"", true);
    text.flush(shapes);
}

// The outline of a rectangle with rounded corners, clockwise from the middle of its top edge.
std::vector<glm::vec2> rounded_rect(const Rect& r, float radius) {
    std::vector<glm::vec2> out{{r.x + r.w / 2, r.y}};
    const glm::vec2 centres[4] = {{r.right() - radius, r.y + radius},
                                  {r.right() - radius, r.bottom() - radius},
                                  {r.x + radius, r.bottom() - radius},
                                  {r.x + radius, r.y + radius}};
    constexpr int steps = 6;
    for (int c = 0; c < 4; ++c)
        for (int i = 0; i <= steps; ++i) {
            const float a = (float(c) - 1 + float(i) / steps) * 1.5707964f;  // -90 degrees: up, y down
            out.push_back(centres[c] + radius * glm::vec2(std::cos(a), std::sin(a)));
        }
    out.push_back(out.front());
    return out;
}

// matplotlib's legend: white at 0.8 alpha in a 0.8 grey rounded frame, half
// an em from the axes' corner; rows of a 2 em line sample and the label.
void draw_legend(TextSink& text, const Rect& frame, const Axes& axes, const PlotStyle& st) {
    std::vector<const Series*> entries;
    for (const Series& s : axes.series)
        if (!s.label.empty()) entries.push_back(&s);
    if (axes.legend == Legend::none || entries.empty()) return;
    Font& font = font_of_size(st.label_size * st.scale);
    const float row = (text_ascent + text_descent) * font.pixel_size();
    const float f = st.legend_em > 0 ? st.legend_em * st.scale : font.pixel_size();  // matplotlib: the legend's font size
    float text_width = 0;
    for (const Series* s : entries) text_width = std::max(text_width, font.width(s->label));
    Rect box{0, 0, 0.4f * f + 2.0f * f + 0.8f * f + text_width + 0.4f * f,
             0.8f * f + float(entries.size()) * row + float(entries.size() - 1) * 0.5f * f};
    const bool left = axes.legend == Legend::upper_left || axes.legend == Legend::lower_left;
    const bool upper = axes.legend == Legend::upper_left || axes.legend == Legend::upper_right;
    box.x = left ? frame.x + 0.5f * f : frame.right() - 0.5f * f - box.w;
    box.y = upper ? frame.y + 0.5f * f : frame.bottom() - 0.5f * f - box.h;

    Shapes shapes;
    const std::vector<glm::vec2> outline = rounded_rect(box, 0.2f * f);
    shapes.convex_polygon(outline, {1, 1, 1, 0.8f});
    shapes.polyline(outline, 1.4f * st.scale, {0.8f, 0.8f, 0.8f, 1});
    text.name(box, "the legend", true);
    if (!text.drawing()) return;  // its entries lie inside its box
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const Series& s = *entries[i];
        const float baseline = box.y + 0.4f * f + float(i) * (row + 0.5f * f) + text_ascent * font.pixel_size();
        const float y = baseline - 0.35f * f, x0 = box.x + 0.4f * f, x1 = x0 + 2.0f * f;
        const std::vector<glm::vec2> sample{{x0, y}, {x1, y}};
        if (s.line_width > 0)
            shapes.polyline(sample, s.line_width * st.scale, s.colour, scaled(s.dash, st.scale), 0,
                            s.dash.empty() ? LineCap::square : LineCap::butt);
        if (s.marker_size > 0)
            add_marker(shapes, {(x0 + x1) / 2, y}, s.marker_size * st.scale / 2, st.marker_edge * st.scale, s.colour);
        text.add(font, s.label, {x1 + 0.8f * f, baseline}, st.ink);
    }
    text.flush(shapes);
}

// draw_axes through `text`: onto its surface, or its text onto its page.
void lay_out_axes(TextSink& text, const Rect& frame, const Axes& axes, const PlotStyle& style) {
    if (!(frame.w > 0 && frame.h > 0)) return;
    const auto [x_lo, x_hi] = view_range(axes, true);
    const auto [y_lo, y_hi] = view_range(axes, false);
    const AxisMap mx{axes.x_scale, x_lo, x_hi, frame.x, frame.right()};
    // y up on the page, or down (the low end at the top).
    const AxisMap my{axes.y_scale, y_lo, y_hi, axes.y_down ? frame.y : frame.bottom(),
                     axes.y_down ? frame.bottom() : frame.y};
    if (text.drawing()) draw_data(*text.surface(), frame, axes, mx, my, style);
    draw_decorations(text, frame, axes, mx, my, style);
    draw_legend(text, frame, axes, style);
}

}  // namespace

void draw_axes(Surface& surface, const Rect& frame, const Axes& axes, const PlotStyle& style) {
    TextSink text(surface);
    lay_out_axes(text, frame, axes, style);
}

void axes_text(PageText& page, const Rect& frame, const Axes& axes, const PlotStyle& style, int plot) {
    const std::string name = plot > 0 ? "plot " + std::to_string(plot) : "the plot";
    page.panels.push_back({frame, "the frame of " + name});
    TextSink text(page, static_cast<int>(page.panels.size()) - 1, plot > 0 ? " of " + name : "");
    lay_out_axes(text, frame, axes, style);
}

std::vector<Rect> plot_row(int width, int height, int count, const PlotStyle& style, float min_left,
                           float min_gap) {
    if (count < 1) return {};
    const float s = style.scale, f = style.font_size * s, lf = style.label_size * s;
    const float tick_room = (style.major_tick + style.tick_pad) * s;
    // Room for tick labels of up to 2.6 ems ("10⁵" is about 2) and the axis
    // labels, where the page is too small for matplotlib's fractions.
    const float need_left = tick_room + 2.6f * f + style.label_pad * s + 1.2f * lf;
    const float need_bottom = tick_room + f + style.label_pad * s + 1.2f * lf;
    const float need_top = style.title_pad * s + 1.2f * style.title_size * s;
    const float W = float(width), H = float(height);
    const float left = std::max({style.left * W, need_left, min_left}), right = std::max((1 - style.right) * W, 1.2f * f);
    const float top = std::max((1 - style.top) * H, need_top), bottom = std::max(style.bottom * H, need_bottom);
    const float n = float(count);
    // The gaps are wspace panel widths, or enough for the y tick labels.
    float w = (W - left - right) / (n + style.wspace * (n - 1));
    float gap = style.wspace * w;
    if (count > 1 && gap < std::max(tick_room + 2.0f * f, min_gap)) {
        gap = std::max(tick_room + 2.0f * f, min_gap);
        w = (W - left - right - gap * (n - 1)) / n;
    }
    const float panel_w = std::max(1.0f, std::floor(w)), panel_h = std::max(1.0f, std::round(H - top - bottom));
    std::vector<Rect> frames;
    for (int i = 0; i < count; ++i)
        frames.push_back({std::round(left + float(i) * (w + gap)), std::round(top), panel_w, panel_h});
    return frames;
}

namespace {

void check_bar(const ColourBar& bar) {
    if (!(std::isfinite(bar.low) && std::isfinite(bar.high) && bar.low < bar.high))
        throw std::invalid_argument("draw_colour_bar: its range must be finite, low below high");
    if (bar.colormap.colours.empty()) throw std::invalid_argument("draw_colour_bar: the colormap has no colours");
}

// The bar's own rectangle beside `field`, whole pixels wide.
Rect bar_rect(const Rect& field) {
    const float gap = std::round(colour_bar_pad * field.w);
    return {field.right() + gap, field.y, std::max(1.0f, std::round(field.h / colour_bar_aspect)), field.h};
}

}  // namespace

std::vector<Tick> colour_bar_ticks(const ColourBar& bar, float height, const PlotStyle& style) {
    check_bar(bar);
    return linear_ticks(bar.low, bar.high, tick_bins(height, style.font_size * style.scale, false)).major;
}

float colour_bar_room(const ColourBar& bar, float field_width, float height, const PlotStyle& st) {
    const float s = st.scale;
    Font& tick_font = font_of_size(st.font_size * s);
    float widest = 0;
    for (const Tick& t : colour_bar_ticks(bar, height, st)) widest = std::max(widest, tick_font.width(t.label));
    float room = std::round(colour_bar_pad * field_width) + std::max(1.0f, std::round(height / colour_bar_aspect)) +
                 (st.major_tick + st.tick_pad) * s + widest;
    if (!bar.label.empty()) room += st.label_pad * s + font_of_size(st.label_size * s).line_height();
    return std::ceil(room);
}

namespace {

// draw_colour_bar through `text`: onto its surface, or its text onto its page.
void lay_out_colour_bar(TextSink& text, const Rect& field, const ColourBar& bar, const PlotStyle& st) {
    check_bar(bar);
    const float s = st.scale;
    const Rect r = bar_rect(field);
    Shapes shapes;
    if (text.drawing()) {
        // The entries as a column of cells, top row the last entry.
        const int n = bar.colormap.size();
        std::vector<double> values(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) values[static_cast<std::size_t>(i)] = n - 1 - i + 0.5;
        const FieldStyle cells{&bar.colormap, 0.0, double(n), 1.0f, Sampling::nearest};
        draw_field(*text.surface(), r, n, 1, values, cells);
        shapes.frame(r, st.spine_width * s, st.ink);
    }
    Font& tick_font = font_of_size(st.font_size * s);
    float widest = 0;
    const float tick_length = st.major_tick * s, tick_width = st.major_tick_width * s;
    for (const Tick& t : colour_bar_ticks(bar, r.h, st)) {
        const float y = snap(float(r.bottom() - (t.value - bar.low) / (bar.high - bar.low) * r.h), tick_width);
        shapes.line({r.right(), y}, {r.right() + tick_length, y}, tick_width, st.ink);
        text.name(text.add(tick_font, t.label, {r.right() + tick_length + st.tick_pad * s, y}, st.ink, Align::left,
                           Baseline::middle),
                  "the colour bar's tick label \"" + t.label + "\"");
        widest = std::max(widest, tick_font.width(t.label));
    }
    if (!bar.label.empty()) {
        Font& label_font = font_of_size(st.label_size * s);
        // Turned to read upwards, its top towards the ticks (matplotlib puts a
        // vertical colorbar's label on the right, rotated 90 degrees).
        const float x = r.right() + tick_length + st.tick_pad * s + widest + st.label_pad * s;
        text.name(text.add(label_font, bar.label, {x, r.centre().y}, st.ink, Align::centre, Baseline::top, 90),
                  "the colour bar's label");
    }
    text.flush(shapes);
}

}  // namespace

void draw_colour_bar(Surface& surface, const Rect& field, const ColourBar& bar, const PlotStyle& st) {
    TextSink text(surface);
    lay_out_colour_bar(text, field, bar, st);
}

void colour_bar_text(PageText& page, const Rect& field, const ColourBar& bar, const PlotStyle& style, int panel) {
    const std::string of = panel > 0 ? " of panel " + std::to_string(panel) : "";
    page.panels.push_back({bar_rect(field), "the colour bar" + of});
    TextSink text(page, static_cast<int>(page.panels.size()) - 1, of);
    lay_out_colour_bar(text, field, bar, style);
}

}  // namespace render
