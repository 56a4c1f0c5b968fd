// Runs a compiled formula (sim/formula/program.hpp) over the grid: rows in
// chunks of up to chunk_lanes cells, each chain in one pass over the chunk
// (sim/formula/chain_kernels.hpp), each other operation a loop over it (vectorised
// by the compiler, a clone per instruction set), the rows of a step split
// among threads (sim/parallel_steps.hpp). A 2-D grid's steps go in blocks
// of up to 32, each band of rows advancing a block's steps while it is in
// the core's cache (blocked_steps), with the same bits.
//
// Neighbours: each chemical's rows are stored with `radius_x` cells of halo
// on both sides, filled after each row is written as Ready's indexing reads
// them, so that a neighbour at offset dx is the row read dx cells along;
// rows at (dy, dz) are looked up in a table made once. A 3-D grid is its
// rows one plane after another (the row of (y, z) is z * height + y).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <tuple>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sim/formula/run.hpp"
#include "sim/formula/chain_kernels.hpp"
#include "sim/formula/program.hpp"
#include "sim/formula/scalar.hpp"
#include "sim/parallel_steps.hpp"

namespace sim::formula {

namespace {

#if defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__) && !defined(__clang__)
#define FIGGEN_FORMULA_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define FIGGEN_FORMULA_CLONES
#endif

// A division by the cells' values (chains, sim/formula/chain_kernels.hpp, take
// the rest of the arithmetic): a / b, k / b or a / k, one loop each.
template <class Real>
void divide_rows(Real* __restrict d, const Real* __restrict a, const Real* __restrict b, int n) {
    for (int i = 0; i < n; ++i) d[i] = a[i] / b[i];
}
template <class Real>
void divide_left(Real* __restrict d, Real k, const Real* __restrict b, int n) {
    for (int i = 0; i < n; ++i) d[i] = k / b[i];
}
template <class Real>
void divide_right(Real* __restrict d, const Real* __restrict a, Real k, int n) {
    for (int i = 0; i < n; ++i) d[i] = a[i] / k;
}
FIGGEN_FORMULA_CLONES void divide_f(float* d, const float* a, const float* b, float k, int n) {
    a ? b ? divide_rows(d, a, b, n) : divide_right(d, a, k, n) : divide_left(d, k, b, n);
}
FIGGEN_FORMULA_CLONES void divide_d(double* d, const double* a, const double* b, double k, int n) {
    a ? b ? divide_rows(d, a, b, n) : divide_right(d, a, k, n) : divide_left(d, k, b, n);
}

// d = (+/-)a * b (+/-) c, rounded once, in clones that have the processor's
// fused multiply-add (x86-64-v3 and v4) and one that calls libm's fma.
#if defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__) && !defined(__clang__)
#define FIGGEN_FMA_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define FIGGEN_FMA_CLONES
#endif
template <class Real>
void fma_rows(Real* __restrict d, const Real* __restrict a, const Real* __restrict b, const Real* __restrict c,
              std::uint8_t signs, int n) {
    const Real sx = (signs & Instr::negate_product) ? Real(-1) : Real(1);
    const Real sc = (signs & Instr::negate_addend) ? Real(-1) : Real(1);
    for (int i = 0; i < n; ++i) d[i] = std::fma(sx * a[i], b[i], sc * c[i]);  // sign changes are exact
}
FIGGEN_FMA_CLONES void fma_f(float* d, const float* a, const float* b, const float* c, std::uint8_t signs, int n) {
    fma_rows(d, a, b, c, signs, n);
}
FIGGEN_FMA_CLONES void fma_d(double* d, const double* a, const double* b, const double* c, std::uint8_t signs, int n) {
    fma_rows(d, a, b, c, signs, n);
}
template <class Real>
void fused_multiply_add(Real* d, const Real* a, const Real* b, const Real* c, std::uint8_t signs, int n) {
    if constexpr (sizeof(Real) == 4) fma_f(d, a, b, c, signs, n);
    else fma_d(d, a, b, c, signs, n);
}

// Whether any of b's n values is zero where the mask (if any) is nonzero,
// and whether any of v's is not a finite number: branch-free, vectorised.
#define FIGGEN_FORMULA_CHECKS(REAL, SUFFIX)                                                     \
    FIGGEN_FORMULA_CLONES int zero_where##SUFFIX(const REAL* __restrict b, const REAL* __restrict mask, int n) { \
        int any = 0;                                                                            \
        if (mask)                                                                               \
            for (int i = 0; i < n; ++i) any |= (b[i] == REAL(0)) & (mask[i] != REAL(0));        \
        else                                                                                    \
            for (int i = 0; i < n; ++i) any |= b[i] == REAL(0);                                 \
        return any;                                                                             \
    }                                                                                           \
    FIGGEN_FORMULA_CLONES int copy_finite##SUFFIX(REAL* __restrict out, const REAL* __restrict v, int n) { \
        int bad = 0;                                                                            \
        for (int i = 0; i < n; ++i) {                                                           \
            out[i] = v[i];                                                                      \
            bad |= (v[i] - v[i]) != REAL(0); /* inf - inf and NaN - NaN are NaN */              \
        }                                                                                       \
        return bad;                                                                             \
    }
FIGGEN_FORMULA_CHECKS(float, _f)
FIGGEN_FORMULA_CHECKS(double, _d)

// A stage's deltas k into the sum that becomes the new state and the next
// stage's state (Engine::combine): sum = from + w k (from: the state x at
// the first stage, else the sum itself), out = x + v k; at the last stage
// the sum alone. Each operation rounded (no contraction: -ffp-contract=off);
// whether a value written is not finite. Branch-free, vectorised: the mask
// as wide as a number, so that no lane's comparison needs packing.
#define FIGGEN_FORMULA_STAGES(REAL, MASK, SUFFIX)                                                          \
    FIGGEN_FORMULA_CLONES int stage_next##SUFFIX(REAL* sum, REAL* __restrict out, const REAL* from,         \
                                                 const REAL* __restrict x, const REAL* __restrict k, REAL w, \
                                                 REAL v, int n) {                                          \
        MASK bad = 0;                                                                                      \
        for (int i = 0; i < n; ++i) {                                                                      \
            const REAL s = from[i] + w * k[i], o = x[i] + v * k[i];                                        \
            sum[i] = s;                                                                                    \
            out[i] = o;                                                                                    \
            bad |= ((s - s) != REAL(0)) | ((o - o) != REAL(0));                                            \
        }                                                                                                  \
        return bad != 0;                                                                                   \
    }                                                                                                      \
    FIGGEN_FORMULA_CLONES int stage_last##SUFFIX(REAL* __restrict sum, const REAL* __restrict k, REAL w, int n) { \
        MASK bad = 0;                                                                                      \
        for (int i = 0; i < n; ++i) {                                                                      \
            const REAL s = sum[i] + w * k[i];                                                              \
            sum[i] = s;                                                                                    \
            bad |= (s - s) != REAL(0);                                                                     \
        }                                                                                                  \
        return bad != 0;                                                                                   \
    }
FIGGEN_FORMULA_STAGES(float, std::int32_t, _f)
FIGGEN_FORMULA_STAGES(double, std::int64_t, _d)

template <class Real>
int stage_next(Real* sum, Real* out, const Real* from, const Real* x, const Real* k, Real w, Real v, int n) {
    if constexpr (sizeof(Real) == 4) return stage_next_f(sum, out, from, x, k, w, v, n);
    else return stage_next_d(sum, out, from, x, k, w, v, n);
}
template <class Real>
int stage_last(Real* sum, const Real* k, Real w, int n) {
    if constexpr (sizeof(Real) == 4) return stage_last_f(sum, k, w, n);
    else return stage_last_d(sum, k, w, n);
}
FIGGEN_FORMULA_CLONES int not_finite_f(const float* __restrict v, int n) {
    int bad = 0;
    for (int i = 0; i < n; ++i) bad |= (v[i] - v[i]) != 0.0f;
    return bad;
}
FIGGEN_FORMULA_CLONES int not_finite_d(const double* __restrict v, int n) {
    int bad = 0;
    for (int i = 0; i < n; ++i) bad |= (v[i] - v[i]) != 0.0;
    return bad;
}

template <class Real>
int zero_where(const Real* b, const Real* mask, int n) {
    if constexpr (sizeof(Real) == 4) return zero_where_f(b, mask, n);
    else return zero_where_d(b, mask, n);
}
template <class Real>
int not_finite(const Real* v, int n) {
    if constexpr (sizeof(Real) == 4) return not_finite_f(v, n);
    else return not_finite_d(v, n);
}
template <class Real>
int copy_finite(Real* out, const Real* v, int n) {
    if constexpr (sizeof(Real) == 4) return copy_finite_f(out, v, n);
    else return copy_finite_d(out, v, n);
}

// d = a / b; a null a or b is the constant k.
template <class Real>
void divide(Real* d, const Real* a, const Real* b, Real k, int n) {
    if constexpr (sizeof(Real) == 4) divide_f(d, a, b, k, n);
    else divide_d(d, a, b, k, n);
}

// A chemical's rows with their halo, and which row a row's neighbour at dy is.
template <class Real>
struct Rows {
    int width = 0, height = 0, halo = 0;
    std::ptrdiff_t stride = 0, offset = 0;  // offset: the padding before row 0
    std::unique_ptr<Real[]> cells;
    Real* row(int y) { return cells.get() + offset + static_cast<std::ptrdiff_t>(y) * stride + halo; }
    const Real* row(int y) const { return cells.get() + offset + static_cast<std::ptrdiff_t>(y) * stride + halo; }
};

// Where Ready reads the cell at t (a column, -halo .. width + halo - 1) of a
// row: its blocks of `block` cells clamped or wrapped with `& (blocks - 1)`,
// the place in the block kept.
int ready_column(int t, int width, int block, bool wrap) {
    const int blocks = width / block;
    const int b = (t >= 0 ? t / block : -((-t + block - 1) / block));
    const int lane = t - b * block;
    const int source_block = wrap ? ((b + blocks) & (blocks - 1)) : std::min(blocks - 1, std::max(0, b));
    return source_block * block + lane;
}

int ready_row(int y, int height, bool wrap) {
    return wrap ? ((y + height) & (height - 1)) : std::min(height - 1, std::max(0, y));
}

// What the cell at t of an axis of n cells (0: x, 1: y, 2: z) reads with
// figgen's own edges (Edges): the cell `source` inside, its value times
// `sign`, plus twice the value of the dirichlet side `side` (-1: none).
struct Past {
    int source, sign, side;
};
Past own_source(int t, int n, const Edges& edges, int axis) {
    if ((t >= 0 && t < n) || n == 1) return {n == 1 ? 0 : t, 1, -1};
    const int side = 2 * axis + (t < 0 ? 0 : 1);
    const Edge edge = edges.side[static_cast<std::size_t>(side)].edge;
    if (edge == Edge::periodic) return {((t % n) + n) % n, 1, -1};
    if (edge == Edge::clamped) return {t < 0 ? 0 : n - 1, 1, -1};
    const int mirrored = t < 0 ? -1 - t : 2 * n - 1 - t;
    if (mirrored < 0 || mirrored >= n)
        throw std::invalid_argument(std::string("the grid is ") + std::to_string(n) + " cells along " +
                                    "xyz"[axis] + ", fewer than its stencils reach past its " + edge_name(edge) +
                                    " " + side_name(side) + " side (" + std::to_string(t < 0 ? -t : t - n + 1) +
                                    " cells)");
    return {mirrored, edge == Edge::dirichlet ? -1 : 1, edge == Edge::dirichlet ? side : -1};
}

// Whether blocked_steps may run (the tests compare it with plain_steps).
std::atomic<bool>& blocking_switch() {
    static std::atomic<bool> on{true};
    return on;
}
bool temporal_blocking() {
    return blocking_switch().load(std::memory_order_relaxed);
}

}  // namespace

struct Run::Impl {
    virtual ~Impl() = default;
    virtual void step(int steps, int threads) = 0;
    virtual int block_steps() const = 0;
    virtual Grid<double> chemical(int i) const = 0;
    long long steps = 0;
    int width = 0, height = 0, depth = 1, operations = 0, chemicals = 0;
};

namespace {

template <class Real>
class Engine final : public Run::Impl {
public:
    Engine(const Rule& rule, Program program, int w, int h, int d, const std::vector<Grid<double>>& start)
        : rule_(rule), program_(std::move(program)), id_(next_id()) {
        chemicals = rule.chemicals;
        width = w;
        height = h;
        depth = d;
        rows_ = h * d;
        operations = program_.operations;
        // The instruction that makes a chemical's new value writes it
        // straight into the chemical's next rows (no copy after), where it
        // is the register's last writer and nothing reads the register
        // after it, nor another chemical's output shares it.
        writes_output_.assign(program_.code.size(), -1);
        for (int chem = 0; chem < rule.chemicals && !program_.outputs_are_deltas; ++chem) {
            const int reg = program_.outputs[static_cast<std::size_t>(chem)];
            int last = -1;
            for (std::size_t i = 0; i < program_.code.size(); ++i)
                if (program_.code[i].dst == reg) last = static_cast<int>(i);
            bool alone = last >= 0;
            for (std::size_t i = static_cast<std::size_t>(last + 1); alone && i < program_.code.size(); ++i) {
                const Instr& in = program_.code[i];
                alone = !reads(in, reg);
            }
            for (int other = 0; other < rule.chemicals; ++other)
                alone = alone && (other == chem || program_.outputs[static_cast<std::size_t>(other)] != reg);
            if (alone) writes_output_[static_cast<std::size_t>(last)] = chem;
        }
        constant_.assign(static_cast<std::size_t>(program_.registers), 0);
        value_.assign(static_cast<std::size_t>(program_.registers), Real(0));
        for (const Program::Constant& c : program_.constants) {
            constant_[static_cast<std::size_t>(c.reg)] = 1;
            value_[static_cast<std::size_t>(c.reg)] = static_cast<Real>(c.value);
        }
        for (const Chain& chain : program_.chains) {
            if constexpr (sizeof(Real) == 4) plans_.push_back(fused::plan_float(program_, chain));
            else plans_.push_back(fused::plan_double(program_, chain));
        }
        halo_ = program_.radius_x;
        const std::ptrdiff_t per_line = 64 / sizeof(Real);
        stride_ = (w + 2 * halo_ + per_line - 1) / per_line * per_line;
        // Several rows make one chunk where a row is short, so that each
        // operation's loop is long: the rows with their halos (and the
        // padding to the next row) are one run of memory, the lanes outside
        // the grid computed and thrown away.
        // As many rows as fit, or fewer that make whole blocks of 64 cells
        // for the chains' vector code (sim/formula/chain_kernels.hpp).
        group_most_ = stride_ <= max_lanes ? static_cast<int>(max_lanes / stride_) : 1;
        for (int rows = group_most_; rows >= 2; --rows)
            if (rows * stride_ % 64 == 0) {
                group_most_ = rows;
                break;
            }
        lanes_ = stride_ <= max_lanes ? static_cast<int>(group_most_ * stride_) : max_lanes;
        // A chunk of whole padded rows (one, where only one fits) starts on
        // a cache line: its stores are aligned, none split between lines.
        padded_ = stride_ <= max_lanes;
        const bool ready = rule.ready_edges && !rule.edges;
        const Edges edges = rule.own_edges();
        // The value of a dirichlet side for chemical c, twice (a mirrored cell is 2 value - the cell).
        auto twice = [&](int side, int c) {
            return side < 0 ? 0.0 : 2 * edges.side[static_cast<std::size_t>(side)].value[static_cast<std::size_t>(c)];
        };
        halo_source_.resize(static_cast<std::size_t>(2 * halo_));
        halo_sign_.assign(static_cast<std::size_t>(2 * halo_), Real(1));
        halo_offset_.assign(static_cast<std::size_t>(2 * halo_ * rule.chemicals), Real(0));
        for (int i = 0; i < 2 * halo_; ++i) {
            const int t = i < halo_ ? -halo_ + i : w + i - halo_;
            if (ready) {
                halo_source_[static_cast<std::size_t>(i)] = ready_column(t, w, rule.block_x, rule.wrap);
                continue;
            }
            const Past past = own_source(t, w, edges, 0);
            halo_source_[static_cast<std::size_t>(i)] = past.source;
            halo_sign_[static_cast<std::size_t>(i)] = static_cast<Real>(past.sign);
            for (int c = 0; c < rule.chemicals; ++c)
                halo_offset_[static_cast<std::size_t>(c * 2 * halo_ + i)] = static_cast<Real>(twice(past.side, c));
        }
        // The row of each neighbour at (dy, dz), z as y is: wrapped or clamped,
        // or mirrored; a row's neighbours side by side (a chunk reads them
        // all: 27 in 3-D). Past a dirichlet side the row read is a ghost (a
        // row after the grid's), rewritten from the row it mirrors each time
        // that row is written (write_ghosts).
        tables_ = (2 * program_.radius_z + 1) * (2 * program_.radius_y + 1);
        row_at_.assign(static_cast<std::size_t>(rows_) * static_cast<std::size_t>(tables_), 0);
        std::vector<std::tuple<int, int, int>> ghost_keys;  // (source row, y side, z side)
        for (int dz = -program_.radius_z; dz <= program_.radius_z; ++dz)
            for (int dy = -program_.radius_y; dy <= program_.radius_y; ++dy) {
                const int table = (dz + program_.radius_z) * (2 * program_.radius_y + 1) + dy + program_.radius_y;
                for (int z = 0; z < d; ++z)
                    for (int y = 0; y < h; ++y) {
                        int row = 0;
                        if (ready) {
                            row = ready_row(z + dz, d, rule.wrap) * h + ready_row(y + dy, h, rule.wrap);
                        } else {
                            const Past py = own_source(y + dy, h, edges, 1), pz = own_source(z + dz, d, edges, 2);
                            row = pz.source * h + py.source;
                            // The value sz (sy u + oy) + oz, y's mirror first.
                            Ghost ghost{row, static_cast<Real>(py.sign * pz.sign), {}, true};
                            for (int c = 0; c < rule.chemicals; ++c) {
                                const double offset = pz.sign * twice(py.side, c) + twice(pz.side, c);
                                ghost.offset.push_back(static_cast<Real>(offset));
                                ghost.plain = ghost.plain && offset == 0;
                            }
                            ghost.plain = ghost.plain && ghost.sign == Real(1);
                            if (!ghost.plain) {
                                const std::tuple<int, int, int> key{row, py.side, pz.side};
                                const auto at = std::find(ghost_keys.begin(), ghost_keys.end(), key);
                                row = rows_ + static_cast<int>(at - ghost_keys.begin());
                                if (at == ghost_keys.end()) {
                                    ghost_keys.push_back(key);
                                    ghosts_.push_back(std::move(ghost));
                                }
                            }
                        }
                        row_at_[static_cast<std::size_t>(z * h + y) * static_cast<std::size_t>(tables_) +
                                static_cast<std::size_t>(table)] = row;
                    }
            }
        // Each row's ghosts, together (ghost_begin_[r] .. ghost_begin_[r + 1] of ghost_order_).
        if (!ghosts_.empty()) {
            ghost_begin_.assign(static_cast<std::size_t>(rows_) + 1, 0);
            for (const Ghost& g : ghosts_) ++ghost_begin_[static_cast<std::size_t>(g.source) + 1];
            for (int r = 0; r < rows_; ++r) ghost_begin_[r + 1] += ghost_begin_[r];
            ghost_order_.resize(ghosts_.size());
            std::vector<int> next(ghost_begin_.begin(), ghost_begin_.end() - 1);
            for (int g = 0; g < static_cast<int>(ghosts_.size()); ++g)
                ghost_order_[static_cast<std::size_t>(next[static_cast<std::size_t>(ghosts_[g].source)]++)] = g;
        }
        for (int k = 0; k < 2; ++k)
            for (int c = 0; c < rule.chemicals; ++c) state_[k].push_back(make_rows());
        for (int y = 0; y < rows_; ++y) {
            for (int c = 0; c < rule.chemicals; ++c) {
                Real* row = state_[0][c].row(y);
                for (int x = 0; x < w; ++x) row[x] = static_cast<Real>(start[c](y, x));
                fill_halo(row, c);
            }
            write_ghosts(state_[0], y);
        }
        if (program_.outputs_are_deltas) {
            // A step of several stages: each stage's state (two in turn for RK4).
            stages_ = stages(rule.integrator);
            timestep_ = formula_value(rule.parameter("timestep"));  // as Euler's formula reads it
            for (int k = 0; k < (stages_ > 2 ? 2 : 1); ++k)
                for (int c = 0; c < rule.chemicals; ++c) stage_[k].push_back(make_rows());
        } else {
            plan_blocks();
        }
        if (bands_ > 0)
            for (int c = 0; c < rule.chemicals; ++c) state_[2].push_back(make_rows());
        // Row r follows row r - 1 in memory for every neighbour row: they can share a chunk.
        follows_.assign(static_cast<std::size_t>(rows_), 0);
        for (int r = 1; r < rows_; ++r) {
            bool follows = true;
            const int* now = neighbour_rows(r);
            const int* before = neighbour_rows(r - 1);
            for (int t = 0; t < tables_; ++t) follows &= now[t] == before[t] + 1;
            follows_[r] = follows;
        }
        // x_pos as Ready computes it, for every lane of a chunk of rows (0 outside the grid).
        if (program_.x_pos >= 0) {
            x_pos_.assign(static_cast<std::size_t>(std::max<std::ptrdiff_t>(lanes_, stride_)) + 64, Real(0));
            for (int r = 0; r < group_most_; ++r)
                for (int x = 0; x < w; ++x) {
                    Real value;
                    if (rule.block_x == 4)
                        value = (static_cast<Real>(x / 4) + static_cast<Real>(x % 4) * Real(0.25)) /
                                static_cast<Real>(w / 4);
                    else
                        value = static_cast<Real>(x) / static_cast<Real>(w);
                    if (padded_) x_pos_[static_cast<std::size_t>(r * stride_ + halo_ + x)] = value;
                    else x_pos_[static_cast<std::size_t>(x)] = value;
                }
        }
    }

    void step(int steps_wanted, int threads) override {
        if (steps_wanted <= 0) return;
        if (stages_ > 1) return staged_steps(steps_wanted, threads);
        if (bands_ > 0 && temporal_blocking() && steps_wanted > 1) blocked_steps(steps_wanted, threads);
        else plain_steps(steps_wanted, threads);
    }

    // Step by step: the rows of each step split among the threads, a
    // barrier between steps; current_ and one other buffer in turn.
    void plain_steps(int steps_wanted, int threads) {
        Failure failure;
        failure.base = steps;
        const int first = current_, second = bands_ > 0 ? (current_ + 1) % 3 : current_ ^ 1;
        auto buffer = [&](int s) { return (s & 1) ? second : first; };  // the state after s steps of this call
        parallel_steps(rows_, steps_wanted, threads, [&](int s, int begin, int end) {
            // A failed step still ends on every thread (the first cell in
            // row order wins, whatever the timing); no later step runs.
            if (failure.failed_step.load(std::memory_order_relaxed) < s) return;
            // Ready builds with -cl-denorms-are-zero: float flushes
            // subnormals; double keeps them (and so equals figgen's own
            // double models).
            std::optional<SubnormalsFlushed> flushed;
            if constexpr (sizeof(Real) == 4) flushed.emplace();
            Scratch& scratch = this->scratch();
            rows_of_step(s, begin, end, state_[buffer(s)], state_[buffer(s + 1)], scratch, failure);
        });
        if (failure.failed.load()) {
            // The state stays the failed step's input.
            const long long done = failure.step - failure.base;  // steps of this call that completed
            steps = failure.step;
            current_ = buffer(static_cast<int>(done));
            throw Unstable(failure.message);
        }
        steps += steps_wanted;
        current_ = buffer(steps_wanted);
    }

    // Heun's method and RK4: each step in stages_ stages, a barrier after
    // each (a stage reads its neighbours' values of the stage before). The
    // program gives the deltas k of a stage's state; the chunk combines
    // them (chunk's Stage) into the next stage's state, and into the sum
    // that becomes the new state, kept in the buffer the step writes:
    //   heun: S = X + h k1,  X' = (X + h/2 k1) + h/2 k2 (k2 from S);
    //   rk4:  S1 = X + h/2 k1, S2 = X + h/2 k2, S3 = X + h k3,
    //         X' = X + h/6 k1 + h/3 k2 + h/3 k3 + h/6 k4,
    // added in that order, each operation rounded to the number type. The
    // state X is only read until the step ends: a stage that fails leaves
    // it as the failed step's input.
    void staged_steps(int steps_wanted, int threads) {
        Failure failure;
        failure.base = steps;
        const int first = current_, second = current_ ^ 1;
        auto buffer = [&](int s) { return (s & 1) ? second : first; };  // the state after s steps of this call
        std::atomic<long long> failed_phase{std::numeric_limits<long long>::max()};
        parallel_steps(rows_, steps_wanted * stages_, threads, [&](int phase, int begin, int end) {
            if (failed_phase.load(std::memory_order_relaxed) < phase) return;
            std::optional<SubnormalsFlushed> flushed;
            if constexpr (sizeof(Real) == 4) flushed.emplace();
            Scratch& scratch = this->scratch();
            const int s = phase / stages_, q = phase % stages_;
            const bool last = q == stages_ - 1;
            Stage stage{q, &state_[buffer(s)], &state_[buffer(s + 1)]};
            const std::vector<Rows<Real>>& from = q == 0 ? state_[buffer(s)] : stage_[(q - 1) & 1];
            std::vector<Rows<Real>>& to = last ? state_[buffer(s + 1)] : stage_[q & 1];
            if (!rows_of_step(s, begin, end, from, to, scratch, failure, &stage)) {
                long long was = failed_phase.load();
                while (phase < was && !failed_phase.compare_exchange_weak(was, phase)) {
                }
            }
        });
        if (failure.failed.load()) {
            const long long done = failure.step - failure.base;
            steps = failure.step;
            current_ = buffer(static_cast<int>(done));
            throw Unstable(failure.message);
        }
        steps += steps_wanted;
        current_ = buffer(steps_wanted);
    }

    // Temporal blocking (a 2-D grid too large for the caches): the steps in
    // blocks of block_steps_, each block in two phases with a barrier
    // between, instead of a barrier a step. The rows are cut into bands.
    // Phase 0: each band advances the block's steps while it is in the
    // core's cache, the rows it computes at step j shrinking by `reach_`
    // (the farthest row a cell reads) at each end that meets another band,
    // so that it reads only rows it has computed (a trapezoid); right after
    // a band, the rows left between it and the band before (a trapezoid
    // upside down, growing by reach_ each step) where a thread holds both.
    // Phase 1: the same between the threads' bands (and across row 0 when
    // the rows wrap). Every row of every step is computed once, from the
    // same rows as step by step, so the bits are the same on any number of
    // threads. Three buffers: the block's start is only read (step 1 reads
    // it, steps 2, 3, ... go to the other two in turn), so that a failure
    // runs the block again step by step from it, to fail where step by step
    // fails and leave that step's input.
    void blocked_steps(int steps_wanted, int threads) {
        const int k = block_steps_;
        const int blocks = (steps_wanted + k - 1) / k;
        // Each block's start buffer: the last of the block before.
        std::vector<int> start(static_cast<std::size_t>(blocks) + 1, current_);
        for (int b = 0; b < blocks; ++b) {
            const int kk = std::min(k, steps_wanted - b * k);
            const int s = start[static_cast<std::size_t>(b)];
            start[static_cast<std::size_t>(b) + 1] = (kk & 1) ? (s + 1) % 3 : (s + 2) % 3;
        }
        Failure failure;
        failure.base = steps;
        std::atomic<int> failed_block{blocks};
        parallel_steps(bands_, 2 * blocks, threads, [&](int phase_of_run, int band_begin, int band_end) {
            const int b = phase_of_run / 2, phase = phase_of_run % 2;
            if (failure.failed.load(std::memory_order_relaxed)) return;
            std::optional<SubnormalsFlushed> flushed;
            if constexpr (sizeof(Real) == 4) flushed.emplace();
            Scratch& scratch = this->scratch();
            const int kk = std::min(k, steps_wanted - b * k);
            const int s0 = start[static_cast<std::size_t>(b)];
            const int w1 = (s0 + 1) % 3, w2 = (s0 + 2) % 3;
            // The buffer of the state after j steps of the block.
            auto buffer = [&](int j) { return j == 0 ? s0 : (j & 1) ? w1 : w2; };
            // Rows lo .. hi - 1 (taken modulo the rows when they wrap) of the block's step j.
            auto rows = [&](int j, int lo, int hi) {
                if (lo >= hi) return true;
                const int s = b * k + j - 1;
                const std::vector<Rows<Real>>& from = state_[buffer(j - 1)];
                std::vector<Rows<Real>>& to = state_[buffer(j)];
                if (lo < 0)
                    return rows_of_step(s, lo + rows_, rows_, from, to, scratch, failure) &&
                           rows_of_step(s, 0, hi, from, to, scratch, failure);
                return rows_of_step(s, lo, hi, from, to, scratch, failure);
            };
            // The rows between the bands that meet at row `at` (0: across the wrap).
            auto between = [&](int at) {
                for (int j = 2; j <= kk; ++j)
                    if (!rows(j, at - (j - 1) * reach_, at + (j - 1) * reach_)) return false;
                return true;
            };
            bool ok = true;
            if (phase == 0) {
                for (int band = band_begin; ok && band < band_end; ++band) {
                    const int lo = band_row(band), hi = band_row(band + 1);
                    const bool shrink_lo = lo > 0 || wraps_, shrink_hi = hi < rows_ || wraps_;
                    for (int j = 1; ok && j <= kk; ++j)
                        ok = rows(j, lo + (shrink_lo ? (j - 1) * reach_ : 0), hi - (shrink_hi ? (j - 1) * reach_ : 0));
                    if (ok && band > band_begin) ok = between(lo);
                }
            } else if (band_begin < band_end && (band_begin > 0 || wraps_)) {
                ok = between(band_row(band_begin));
            }
            if (!ok) {
                int was = failed_block.load();
                while (b < was && !failed_block.compare_exchange_weak(was, b)) {
                }
            }
        });
        if (failure.failed.load()) {
            // Block failed_block's start is intact: from it, step by step.
            const int b = failed_block.load();
            steps += static_cast<long long>(b) * k;
            current_ = start[static_cast<std::size_t>(b)];
            plain_steps(steps_wanted - b * k, threads);
            throw std::logic_error("a formula's blocked steps failed where its steps one by one do not");
        }
        steps += steps_wanted;
        current_ = start[static_cast<std::size_t>(blocks)];
    }

    // Temporal blocking (blocked_steps) for a 2-D grid where every row
    // reads rows at most a few away (across row 0 and the last where they
    // wrap): the farthest, the block's steps (as many as leave four bands
    // at least, each wider than its two trapezoids upside down) and the
    // bands, each about blocking_band_bytes a state where there are rows
    // enough.
    void plan_blocks() {
        if (depth != 1 || rows_ < 2) return;
        int reach = 0;
        bool wraps = false;
        for (int r = 0; r < rows_; ++r)
            for (int t = 0; t < tables_; ++t) {
                int d = real_row(neighbour_rows(r)[t]) - r;
                if (std::abs(d) > most_reach) {
                    d = d > 0 ? d - rows_ : d + rows_;  // across the wrap
                    if (std::abs(d) > most_reach) return;
                    wraps = true;
                }
                reach = std::max(reach, std::abs(d));
            }
        for (int k = most_block_steps; k >= 2; k /= 2) {
            const int least_band = (2 * k - 1) * reach + 1;  // a band's two trapezoids upside down do not meet
            if (rows_ / least_band < 4) continue;
            const double row_bytes = static_cast<double>(stride_) * sizeof(Real) * chemicals;
            const int band = std::max(least_band, static_cast<int>(blocking_band_bytes / row_bytes));
            bands_ = std::max(rows_ / band, 4);
            block_steps_ = k;
            reach_ = reach;
            wraps_ = wraps;
            return;
        }
    }
    // A band's rows in one state, to stay in a core's cache through a
    // block's steps; at most 32 steps a block. Pearson's Gray-Scott at
    // 1024 x 1024, 1500 steps, against one barrier a step: 0.90 of the
    // time (farm-bench, paired; 16 steps a block against 4: 0.94, 32
    // against 16: 0.96).
    static constexpr double blocking_band_bytes = 128 << 10;
    static constexpr int most_block_steps = 32;
    static constexpr int most_reach = 8;

    // The first row of band i (of bands_).
    int band_row(int band) const {
        return static_cast<int>(static_cast<long long>(rows_) * band / bands_);
    }

    int block_steps() const override { return bands_ > 0 ? block_steps_ : 1; }

    Grid<double> chemical(int i) const override {
        Grid<double> g(rows_, width);
        const Rows<Real>& rows = state_[current_][i];
        for (int y = 0; y < rows_; ++y)
            for (int x = 0; x < width; ++x) g(y, x) = static_cast<double>(rows.row(y)[x]);
        return g;
    }

private:
    static constexpr std::ptrdiff_t max_lanes = chunk_lanes;  // a chunk's cells: each register 8 or 16 KiB

    struct Failure {
        std::atomic<bool> failed{false};
        std::atomic<long long> failed_step{std::numeric_limits<long long>::max()};  // of this call's steps
        std::mutex lock;
        long long step = 0, y = 0, x = 0;
        long long base = 0;  // the run's steps before this call
        std::string message;
        // Keeps the first failure in (step, row, column) order, whatever the threads' timing.
        void record(long long s, int row, int column, std::string what) {
            std::lock_guard<std::mutex> hold(lock);
            if (failed.load() && std::make_tuple(step, y, x) <= std::make_tuple(s, (long long)row, (long long)column))
                return;
            step = s;
            y = row;
            x = column;
            message = std::move(what);
            failed.store(true);
            failed_step.store(s - base);
        }
    };

    // Registers a chunk and a cache line apart, not a power of two: loads
    // and stores 4 KiB apart alias in the core's store forwarding.
    std::ptrdiff_t register_stride() const { return lanes_ + 64 / static_cast<std::ptrdiff_t>(sizeof(Real)); }

    struct Scratch {
        std::vector<Real> buffers;
        std::vector<Real*> reg;
        std::vector<const Real*> view;
        std::uint64_t owner = 0;  // the engine whose program the registers hold
    };

    bool reads(const Instr& in, int reg) const {
        for (int r : sources(program_, in))
            if (r == reg) return true;
        return false;
    }

    static std::uint64_t next_id() {
        static std::atomic<std::uint64_t> id{0};
        return ++id;
    }

    Scratch& scratch() {
        thread_local Scratch s;
        if (s.owner != id_) {
            s.owner = id_;
            const std::ptrdiff_t stride = register_stride();
            s.buffers.assign(static_cast<std::size_t>(program_.registers * stride + 64), Real(0));
            s.reg.assign(static_cast<std::size_t>(program_.registers), nullptr);
            Real* base = s.buffers.data();
            const std::uintptr_t misaligned = reinterpret_cast<std::uintptr_t>(base) % 64;
            if (misaligned) base += (64 - misaligned) / sizeof(Real);
            for (int r = 0; r < program_.registers; ++r) s.reg[r] = base + static_cast<std::ptrdiff_t>(r) * stride;
            for (const Program::Constant& c : program_.constants)
                std::fill(s.reg[c.reg], s.reg[c.reg] + lanes_, static_cast<Real>(c.value));
            s.view.assign(s.reg.begin(), s.reg.end());
        }
        return s;
    }

    // Rows of a chemical, with `pad` cells before the first and after the
    // last so that a chunk's lanes outside the grid read memory that exists.
    // Each row's halo starts on a cache line: a chunk's first lane, so that
    // the loads of the cells themselves (not their neighbours in x) and the
    // stores are aligned.
    Rows<Real> make_rows() const {
        Rows<Real> r;
        r.width = width;
        r.height = rows_;
        r.halo = halo_;
        r.stride = stride_;
        const std::ptrdiff_t line = 64 / static_cast<std::ptrdiff_t>(sizeof(Real));
        const std::ptrdiff_t pad = (stride_ + 2 * halo_ + 64 + line - 1) / line * line;
        const std::ptrdiff_t rows = rows_ + static_cast<std::ptrdiff_t>(ghosts_.size());
        r.cells.reset(new Real[static_cast<std::size_t>(stride_ * rows + 2 * pad + line)]());
        const std::uintptr_t misaligned = reinterpret_cast<std::uintptr_t>(r.cells.get()) % 64;
        r.offset = pad + (misaligned ? (64 - static_cast<std::ptrdiff_t>(misaligned)) / static_cast<std::ptrdiff_t>(sizeof(Real)) : 0);
        return r;
    }

    // Chemical c's row's halo: its cells past the left and right sides.
    void fill_halo(Real* row, int c) const {
        const Real* offset = halo_offset_.data() + static_cast<std::ptrdiff_t>(c) * 2 * halo_;
        for (int i = 0; i < 2 * halo_; ++i) {
            Real* to = row + (i < halo_ ? -halo_ + i : width + i - halo_);
            const Real from = row[halo_source_[static_cast<std::size_t>(i)]];
            // A plain copy keeps a negative zero (Ready's bits), which -0 + 0 would not.
            *to = halo_sign_[static_cast<std::size_t>(i)] == Real(1) && offset[i] == Real(0)
                      ? from
                      : halo_sign_[static_cast<std::size_t>(i)] * from + offset[i];
        }
    }

    // The ghost rows that mirror row r past a dirichlet side, from its cells and halo.
    void write_ghosts(std::vector<Rows<Real>>& rows, int r) const {
        if (ghosts_.empty()) return;
        for (int i = ghost_begin_[static_cast<std::size_t>(r)]; i < ghost_begin_[static_cast<std::size_t>(r) + 1]; ++i) {
            const int g = ghost_order_[static_cast<std::size_t>(i)];
            const Ghost& ghost = ghosts_[static_cast<std::size_t>(g)];
            for (int c = 0; c < rule_.chemicals; ++c) {
                const Real* from = rows[c].row(r) - halo_;
                Real* to = rows[c].row(rows_ + g) - halo_;
                const Real sign = ghost.sign, offset = ghost.offset[static_cast<std::size_t>(c)];
                for (int x = 0; x < width + 2 * halo_; ++x) to[x] = sign * from[x] + offset;
            }
        }
    }

    // The cell at column x of row r, as its coordinates: "(x 3, y 5)", "(x 3)" in 1-D, "(x 3, y 5, z 2)" in 3-D.
    std::string cell_name(int x, int r) const {
        std::string name = "(x " + std::to_string(x);
        if (height > 1 || depth > 1) name += ", y " + std::to_string(r % height);
        if (depth > 1) name += ", z " + std::to_string(r / height);
        return name + ")";
    }

    void record_zero(Failure& failure, long long s, int r, int x, const Instr& in, const char* what) {
        failure.record(s, r, x,
                       "step " + std::to_string(s + 1) + ", cell " + cell_name(x, r) + ": " + what + " at line " +
                           std::to_string(in.pos.line) + ", column " + std::to_string(in.pos.column) +
                           " of the formula");
    }

    // A stage of staged_steps: its number, the step's state X, and the
    // buffer of the step's new state, which holds the sum so far.
    struct Stage {
        int q;
        const std::vector<Rows<Real>>* state;
        std::vector<Rows<Real>>* sum;
    };

    // Stage q's deltas k of `cells` cells into the next stage's state `out`
    // and the sum (staged_steps); at the last stage `out` is the sum.
    // False where a value written is not finite.
    bool combine(const Stage& st, const Real* k, const Real* x, Real* sum, Real* out, int cells) const {
        const double h = timestep_;
        const bool rk4 = stages_ == 4;
        // The weight of k in the sum, and in the next stage's state.
        const Real w = static_cast<Real>(rk4 ? ((st.q == 0 || st.q == 3) ? h / 6 : h / 3) : h / 2);
        const Real v = static_cast<Real>(rk4 ? (st.q == 2 ? h : h / 2) : h);
        if (st.q == stages_ - 1) return !stage_last(sum, k, w, cells);
        return !stage_next(sum, out, st.q == 0 ? x : sum, x, k, w, v, cells);
    }

    // Rows begin .. end - 1 of step s (of this call) from `from` into `to`,
    // several to a chunk where they follow in memory; false after a failure.
    bool rows_of_step(int s, int begin, int end, const std::vector<Rows<Real>>& from, std::vector<Rows<Real>>& to,
                      Scratch& scratch, Failure& failure, const Stage* stage = nullptr) {
        for (int y = begin; y < end;) {
            int rows = 1;
            if (group_most_ > 1)
                while (rows < group_most_ && y + rows < end && follows_[y + rows]) ++rows;
            if (!chunk_rows(s, y, rows, from, to, scratch, failure, stage)) return false;
            y += rows;
        }
        return true;
    }

    // Rows y0 .. y0 + rows - 1 of step s (counted from this call's first)
    // from `from` into `to`; false after recording a failure. Several rows
    // go as one chunk of lanes (halos and padding included); a row longer
    // than a chunk goes in pieces.
    bool chunk_rows(int s, int y0, int rows, const std::vector<Rows<Real>>& from, std::vector<Rows<Real>>& to,
                    Scratch& sc, Failure& failure, const Stage* stage) {
        if (padded_) {
            if (!chunk(s, y0, rows, -halo_, static_cast<int>(rows * stride_), from, to, sc, failure, stage))
                return false;
        } else {
            for (int x0 = 0; x0 < width; x0 += static_cast<int>(lanes_))
                if (!chunk(s, y0, 1, x0, std::min(static_cast<int>(lanes_), width - x0), from, to, sc, failure, stage))
                    return false;
        }
        for (int r = 0; r < rows; ++r) {
            for (int chem = 0; chem < rule_.chemicals; ++chem) fill_halo(to[chem].row(y0 + r), chem);
            write_ghosts(to, y0 + r);
        }
        return true;
    }

    // The chunk of `n` lanes from column x0 of row y0 on (rows > 1: whole
    // padded rows from the first's halo). The grid's cells of it are, for
    // each of its rows r, lanes r * stride + (-x0) .. + width (or all n).
    bool chunk(int s, int y0, int rows, int x0, int n, const std::vector<Rows<Real>>& from,
               std::vector<Rows<Real>>& to, Scratch& sc, Failure& failure, const Stage* stage) {
        const Program& p = program_;
        const long long step = steps + s;
        const bool padded = padded_;  // whole padded rows, from the first's halo
        const int first_cell = padded ? -x0 : 0, cells = padded ? width : n;
        auto cell_x = [&](int lane) { return (padded ? lane % static_cast<int>(stride_) - halo_ : x0 + lane); };
        auto cell_y = [&](int lane) { return y0 + (padded ? lane / static_cast<int>(stride_) : 0); };
        const int* neighbours = neighbour_rows(y0);
        for (const Program::Input& in : p.inputs) {
            const int table = (in.dz + p.radius_z) * (2 * p.radius_y + 1) + in.dy + p.radius_y;
            sc.view[in.reg] = from[in.chemical].row(neighbours[table]) + x0 + in.dx;
        }
        if (p.x_pos >= 0) sc.view[p.x_pos] = x_pos_.data() + (padded ? 0 : x0);
        // y_pos and z_pos as Ready computes them: index / size.
        for (const auto& [reg, coordinate, size] : {std::tuple{p.y_pos, 0, height}, std::tuple{p.z_pos, 1, depth}}) {
            if (reg < 0) continue;
            Real* pos = sc.reg[reg];
            for (int r = 0; r < rows; ++r) {
                const int at = coordinate == 0 ? (y0 + r) % height : (y0 + r) / height;
                std::fill(pos + r * (padded ? stride_ : 0), pos + (padded ? (r + 1) * stride_ : n),
                          static_cast<Real>(at) / static_cast<Real>(size));
            }
            sc.view[reg] = pos;
        }
        std::uint32_t verify = ~std::uint32_t(0);  // the chemicals whose new values are still to check
        for (std::size_t k = 0; k < p.code.size(); ++k) {
            const Instr& in = p.code[k];
            const Real* a = in.op != Op::chain && in.a >= 0 ? sc.view[in.a] : nullptr;
            const Real* b = in.b >= 0 ? sc.view[in.b] : nullptr;
            const Real* c = in.c >= 0 ? sc.view[in.c] : nullptr;
            const Real* mask = in.mask >= 0 ? sc.view[in.mask] : nullptr;
            // A chemical's new value straight into its next rows: the
            // chunk's lanes are those rows' memory (halos and padding
            // included, rewritten or unread after).
            const int direct = writes_output_[k];
            Real* d = direct >= 0 ? to[direct].row(y0) + (padded ? -halo_ : x0) : sc.reg[in.dst];
            switch (in.op) {
            case Op::chain:
                // A chain that writes a chemical checks its values as it
                // goes (all lanes: where one is not finite, the grid's
                // cells are checked again below).
                if (!fused::run(plans_[static_cast<std::size_t>(in.a)], sc.view.data(), d, n, direct >= 0) &&
                    direct >= 0)
                    verify &= ~(std::uint32_t(1) << direct);
                break;
            case Op::stencil: throw std::logic_error("a stencil outside a chain");
            case Op::div: {
                // Zero divisors only count on the grid's cells (and where an if lets them through).
                for (int r = 0; r < rows; ++r) {
                    const int begin = r * static_cast<int>(padded ? stride_ : 0) + first_cell;
                    if (zero_where<Real>(b + begin, mask ? mask + begin : nullptr, cells))
                        for (int i = begin; i < begin + cells; ++i)
                            if (b[i] == 0 && (!mask || mask[i] != 0)) {
                                record_zero(failure, step, cell_y(i), cell_x(i), in, "division by zero");
                                return false;
                            }
                }
                if (constant_[in.a]) divide<Real>(d, nullptr, b, value_[in.a], n);
                else if (constant_[in.b]) divide<Real>(d, a, nullptr, value_[in.b], n);
                else divide<Real>(d, a, b, Real(0), n);
                break;
            }
            case Op::copy: std::copy(a, a + n, d); break;
            case Op::neg:
                for (int i = 0; i < n; ++i) d[i] = -a[i];
                break;
            case Op::select:
                for (int i = 0; i < n; ++i) d[i] = c[i] != 0 ? b[i] : a[i];
                break;
            case Op::call1:
                for (int i = 0; i < n; ++i) d[i] = scalar_call<Real>(in.fn, a[i], Real(0), Real(0));
                break;
            case Op::call2:
                for (int i = 0; i < n; ++i) d[i] = scalar_call<Real>(in.fn, a[i], b[i], Real(0));
                break;
            case Op::call3:
                for (int i = 0; i < n; ++i) d[i] = scalar_call<Real>(in.fn, a[i], b[i], c[i]);
                break;
            case Op::fma: fused_multiply_add<Real>(d, a, b, c, in.signs, n); break;
            case Op::int_div:
            case Op::int_mod: {
                for (int r = 0; r < rows; ++r) {
                    const int begin = r * static_cast<int>(padded ? stride_ : 0) + first_cell;
                    for (int i = begin; i < begin + cells; ++i)
                        if (std::trunc(b[i]) == 0 && (!mask || mask[i] != 0)) {
                            record_zero(failure, step, cell_y(i), cell_x(i), in, "integer division by zero");
                            return false;
                        }
                }
                const Real truth = static_cast<Real>(in.truth);
                for (int i = 0; i < n; ++i) d[i] = scalar_op<Real>(in.op, a[i], b[i], truth);
                break;
            }
            default: {
                const Real truth = static_cast<Real>(in.truth);
                for (int i = 0; i < n; ++i) d[i] = scalar_op<Real>(in.op, a[i], b ? b[i] : Real(0), truth);
                break;
            }
            }
            sc.view[in.dst] = d;
        }
        // A stage's deltas combined into the next stage's state (`to`) and
        // the step's sum, each checked.
        if (stage) {
            for (int r = 0; r < rows; ++r) {
                const int begin = r * static_cast<int>(padded ? stride_ : 0) + first_cell;
                for (int chem = 0; chem < rule_.chemicals; ++chem) {
                    const std::ptrdiff_t at = padded ? 0 : x0;
                    Real* out = to[chem].row(y0 + r) + at;
                    if (!combine(*stage, sc.view[p.outputs[chem]] + begin, (*stage->state)[chem].row(y0 + r) + at,
                                 (*stage->sum)[chem].row(y0 + r) + at, out, cells)) {
                        const Real* sum = (*stage->sum)[chem].row(y0 + r) + at;
                        int bad = 0;
                        while (bad + 1 < cells && std::isfinite(out[bad]) && std::isfinite(sum[bad])) ++bad;
                        const Real value = std::isfinite(out[bad]) ? sum[bad] : out[bad];
                        failure.record(step, y0 + r, static_cast<int>(at) + bad,
                                       "step " + std::to_string(step + 1) + ": chemical " + chemical_name(chem) +
                                           " became " + (std::isnan(value) ? "NaN" : "infinite") + " at cell " +
                                           cell_name(static_cast<int>(at) + bad, y0 + r) + " (" +
                                           integrator_name(rule_.integrator) + " stage " + std::to_string(stage->q + 1) +
                                           "): the model is unstable here; try a smaller timestep");
                        return false;
                    }
                }
            }
            return true;
        }
        // The new values of the grid's cells, each checked.
        for (int r = 0; r < rows; ++r) {
            const int begin = r * static_cast<int>(padded ? stride_ : 0) + first_cell;
            for (int chem = 0; chem < rule_.chemicals; ++chem) {
                const Real* v = sc.view[p.outputs[chem]] + begin;
                Real* out = to[chem].row(y0 + r) + (padded ? 0 : x0);
                const bool direct = v == out;
                const bool failed = !direct                                    ? copy_finite<Real>(out, v, cells)
                                    : (verify >> chem & 1) ? not_finite<Real>(out, cells) != 0
                                                           : false;
                // The padding after a row's halo, written with the chunk's
                // other lanes, is zero again: what is computed there never
                // matters, and must not grow into subnormal numbers.
                if (direct && padded) std::fill(out + width + halo_, out - halo_ + stride_, Real(0));
                if (failed) {
                    int bad = 0;
                    while (std::isfinite(v[bad])) ++bad;
                    failure.record(step, y0 + r, (padded ? 0 : x0) + bad,
                                   "step " + std::to_string(step + 1) + ": chemical " + chemical_name(chem) +
                                       " became " + (std::isnan(v[bad]) ? "NaN" : "infinite") + " at cell " +
                                       cell_name((padded ? 0 : x0) + bad, y0 + r) +
                                       ": the model is unstable here; try a smaller timestep");
                    return false;
                }
            }
        }
        return true;
    }

    Rule rule_;
    Program program_;
    std::uint64_t id_;
    int halo_ = 0;
    std::ptrdiff_t stride_ = 0, lanes_ = 0;
    int group_most_ = 1;
    bool padded_ = false;  // a chunk is whole rows with their halos and padding
    int rows_ = 0;  // height * depth
    std::vector<Rows<Real>> state_[3];  // the third only for temporal blocking
    // Heun and RK4 (staged_steps): the stages, their states and the timestep.
    int stages_ = 1;
    double timestep_ = 0;
    std::vector<Rows<Real>> stage_[2];
    int current_ = 0;
    // Temporal blocking (blocked_steps): bands_ > 0 when it runs.
    int bands_ = 0, block_steps_ = 1, reach_ = 0;
    bool wraps_ = false;  // a row near 0 reads rows near the last (and the other way)
    // [row * tables_ + (dz + radius_z) * (2 radius_y + 1) + dy + radius_y]: the row of each neighbour
    std::vector<int> row_at_;
    int tables_ = 1;
    const int* neighbour_rows(int row) const {
        return row_at_.data() + static_cast<std::ptrdiff_t>(row) * tables_;
    }
    std::vector<char> follows_;             // row r follows row r - 1 for every (dy, dz)
    std::vector<int> halo_source_;          // the halo's source columns: left, then right
    std::vector<Real> halo_sign_;           // and each halo cell's value: sign * source + offset
    std::vector<Real> halo_offset_;         // [chemical * 2 halo + i]
    // Rows past a dirichlet side (and past two sides, one of them dirichlet):
    // ghost g is row rows_ + g of every state, sign * row `source` + offset.
    struct Ghost {
        int source;
        Real sign;
        std::vector<Real> offset;  // per chemical
        bool plain;
    };
    std::vector<Ghost> ghosts_;
    std::vector<int> ghost_begin_, ghost_order_;  // each row's ghosts
    // The grid's row a neighbour row is, or mirrors (a ghost).
    int real_row(int row) const {
        return row < rows_ ? row : ghosts_[static_cast<std::size_t>(row - rows_)].source;
    }
    std::vector<Real> x_pos_;
    std::vector<int> writes_output_;  // per instruction: the chemical whose next rows it writes, or -1
    std::vector<fused::Plan<Real>> plans_;  // per chain
    std::vector<char> constant_;  // per register: a constant of the program
    std::vector<Real> value_;     // and its value
};

}  // namespace

Run::Run(const Rule& rule, int width, int height, int depth, const std::vector<Grid<double>>& start) {
    rule.validate(width, height, depth);
    if (static_cast<int>(start.size()) != rule.chemicals)
        throw std::invalid_argument("the start has " + std::to_string(start.size()) + " chemicals, the rule " +
                                    std::to_string(rule.chemicals));
    for (const Grid<double>& g : start)
        if (g.rows() != height * depth || g.cols() != width)
            throw std::invalid_argument("a chemical's start is " + std::to_string(g.cols()) + " x " +
                                        std::to_string(g.rows()) + ", not the grid's " + std::to_string(width) +
                                        " x " + std::to_string(height * depth) + " (height x depth rows)");
    Program program = compile(rule, dimensionality(width, height, depth));
    if (program.radius_x * 2 >= width + 8 || program.radius_y > height * 4 || program.radius_z > depth * 4)
        throw std::invalid_argument("the grid is too small for the formula's stencils");
    if (rule.double_precision)
        impl_ = std::make_unique<Engine<double>>(rule, std::move(program), width, height, depth, start);
    else
        impl_ = std::make_unique<Engine<float>>(rule, std::move(program), width, height, depth, start);
}

void use_temporal_blocking(bool on) {
    blocking_switch().store(on);
}

Run::~Run() = default;
Run::Run(Run&&) noexcept = default;
Run& Run::operator=(Run&&) noexcept = default;

void Run::step(int steps, int threads) {
    if (steps < 0) throw std::invalid_argument("steps is " + std::to_string(steps) + ", not >= 0");
    impl_->step(steps, threads);
}

Grid<double> Run::chemical(int i) const {
    if (i < 0 || i >= impl_->chemicals) throw std::invalid_argument("no chemical " + std::to_string(i));
    return impl_->chemical(i);
}

long long Run::steps() const {
    return impl_->steps;
}
int Run::width() const {
    return impl_->width;
}
int Run::height() const {
    return impl_->height;
}
int Run::depth() const {
    return impl_->depth;
}
int Run::operations() const {
    return impl_->operations;
}
int Run::block_steps() const {
    return impl_->block_steps();
}

}  // namespace sim::formula
