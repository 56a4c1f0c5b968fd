#pragma once
// Where the ticks of a plot axis go and what their labels say, decided as
// matplotlib decides them: AutoLocator + ScalarFormatter on linear axes,
// LogLocator + LogFormatterSciNotation on log axes, and the 5% margins of its
// automatic view limits. Pure functions of numbers: no GL, no fonts.

#include <string>
#include <utility>
#include <vector>

namespace render {

struct Tick {
    double value;       // data units
    std::string label;  // UTF-8; empty: a tick without a label
};

struct AxisTicks {
    std::vector<Tick> major;    // long ticks, in increasing order, all within the range
    std::vector<Tick> minor;    // short ticks; labelled only on log axes shorter than a decade
};

// How many tick intervals fit along an axis `length` pixels long whose tick
// labels are `font_size` pixels: matplotlib's Axis.get_tick_space, which
// leaves three label heights per tick along x and two along y, clipped to 1..9.
int tick_bins(float length, float font_size, bool horizontal);

// Ticks at 1, 2, 2.5 or 5 x 10^k, at most about `bins` intervals apart
// (matplotlib's MaxNLocator with nbins = bins, steps 1, 2, 2.5, 5, 10),
// inside [lo, hi] in either order. Labels have as many decimals as the
// ticks need and all the same ("0.0", "0.2", ...; "0", "100", ...), negative
// ones with a minus sign U+2212. No minor ticks, as matplotlib's default.
AxisTicks linear_ticks(double lo, double hi, int bins = 9);

// Major ticks at powers of ten labelled "10⁰", "10³", "10⁻²" (Unicode
// superscripts), every `stride`-th decade when more than `max_ticks` would
// crowd the axis; minor ticks at 2..9 x 10^k when every decade is labelled,
// at the unlabelled decades otherwise, none beyond ten decades. Throws
// std::invalid_argument unless 0 < lo and 0 < hi.
AxisTicks log_ticks(double lo, double hi, int max_ticks = 9);

// "10" followed by `exponent` in superscript digits: "10⁵", "10⁻³".
std::string power_of_ten_label(int exponent);

// Automatic view limits around data spanning [lo, hi]: 5% of the span added
// on each side (matplotlib's axes.xmargin/ymargin), in log10 space on a log
// axis (lo, hi > 0 there). A single value widens as matplotlib's nonsingular.
std::pair<double, double> linear_auto_range(double lo, double hi);
std::pair<double, double> log_auto_range(double lo, double hi);

// `v` with `decimals` decimals as a figure shows it: "1.57", "\u22121.5" (a
// true minus sign), "0.0" for a negative zero.
std::string format_fixed(double v, int decimals);

}  // namespace render
