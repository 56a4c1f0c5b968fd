#include "sim/check.hpp"
#include "sim/gray_scott_kernels.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace sim {
namespace {

constexpr std::size_t kAlign = 64;  // bytes: a cache line, and a whole number of AVX2/AVX-512 vectors

template <class Real>
struct Rates {
    Real ra, rb, f, fk;  // fk = f + k, rounded once from the double sum (as sim::GrayScott's)
};

// One row of both fields, the halo already in place: a_up, a_mid, a_down
// (and b_*) point at column 0 of the rows above, at and below, whose columns
// -1 and n hold the wrap copies. The arithmetic is sim::GrayScott's, operation
// for operation (laplacian with opposite neighbours paired, then the book's
// order), so the double instantiation gives the same bits. GCC vectorizes the
// loop (-fopt-info-vec: "loop vectorized using 32 byte vectors" in the AVX2
// clone, 16 byte in the default SSE2 one); each lane does the scalar IEEE
// arithmetic (no FMA: -ffp-contract=off), so the vector body and the scalar
// tail agree. target_clones: the binary runs on any x86-64 and uses AVX2
// where the CPU has it, chosen once at load time (same bits either way).
template <class Real>
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
[[gnu::noinline]] void
update_row(const Real* __restrict a_up, const Real* __restrict a_mid, const Real* __restrict a_down,
           const Real* __restrict b_up, const Real* __restrict b_mid, const Real* __restrict b_down,
           Real* __restrict next_a, Real* __restrict next_b, std::ptrdiff_t n, Rates<Real> c) {
    const Real corner = static_cast<Real>(0.05), edge = static_cast<Real>(0.2), one = 1;
#ifdef _OPENMP
#pragma omp simd  // vectorize at -O2 too (GCC 12's -O2 cost model skips this loop); no reduction, so same bits
#endif
    for (std::ptrdiff_t j = 0; j < n; ++j) {
        const std::ptrdiff_t l = j - 1, r = j + 1;
        const Real a_corners = (a_up[l] + a_down[r]) + (a_up[r] + a_down[l]);
        const Real a_edges = (a_up[j] + a_down[j]) + (a_mid[l] + a_mid[r]);
        const Real ca = corner * a_corners + edge * a_edges - a_mid[j];
        const Real b_corners = (b_up[l] + b_down[r]) + (b_up[r] + b_down[l]);
        const Real b_edges = (b_up[j] + b_down[j]) + (b_mid[l] + b_mid[r]);
        const Real cb = corner * b_corners + edge * b_edges - b_mid[j];
        const Real old_a = a_mid[j], old_b = b_mid[j];
        const Real reaction = old_a * (old_b * old_b);
        next_a[j] = old_a + ((c.ra * ca - reaction) + c.f * (one - old_a));
        next_b[j] = old_b + ((c.rb * cb + reaction) - c.fk * old_b);
    }
}

// The end-of-step barrier of the thread team. OpenMP's own barrier spins
// (libgomp's default wait policy), which collapses when the machine is busy:
// a thread that waits for a descheduled partner burns its time slice, ~4 ms
// a step (measured: 2-thread throughput fell from G/s to ~15 M/s with a load
// of 3 on 2 CPUs). This one spins briefly, then sleeps on a futex
// (std::atomic::wait), handing the CPU to the late thread. Release/acquire:
// every row written before arrive() is visible after it.
class StepBarrier {
public:
    // Each thread of the team calls join(omp_get_num_threads()) before its
    // first arrive: all store the same value, so no thread can see a stale
    // size, and no OpenMP barrier is needed to publish it.
    void join(int team) { size_.store(team, std::memory_order_relaxed); }
    void arrive_and_wait() {
        const int size = size_.load(std::memory_order_relaxed);
        const unsigned gen = generation_.load(std::memory_order_acquire);
        if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == size) {
            arrived_.store(0, std::memory_order_relaxed);
            generation_.store(gen + 1, std::memory_order_release);
            generation_.notify_all();
            return;
        }
        for (int i = 0; i < kSpin; ++i) {
            if (generation_.load(std::memory_order_acquire) != gen) return;
#if defined(__x86_64__) || defined(__i386__)
            __builtin_ia32_pause();
#endif
        }
        while (generation_.load(std::memory_order_acquire) == gen) generation_.wait(gen, std::memory_order_acquire);
    }

private:
    static constexpr int kSpin = 4096;  // a few tens of microseconds, about one step at n = 256
    alignas(64) std::atomic<int> arrived_{0};
    alignas(64) std::atomic<unsigned> generation_{0};
    std::atomic<int> size_{1};
};

// The halo of one freshly written row: column -1 copies column n - 1, column n copies column 0.
template <class Real>
inline void wrap_row(Real* row, std::ptrdiff_t n) {
    row[-1] = row[n - 1];
    row[n] = row[0];
}


}  // namespace

template <class Real>
void GrayScottKernel<Real>::AlignedFree::operator()(Real* p) const {
    ::operator delete[](p, std::align_val_t(kAlign));
}

template <class Real>
GrayScottKernel<Real>::GrayScottKernel(const GrayScottParams& params, const Grid<double>& a, const Grid<double>& b)
    : params_(params) {
    params_.validate();
    require_square_field("A", a, params_.n);
    require_square_field("B", b, params_.n);
    const std::ptrdiff_t n = params_.n;
    const std::ptrdiff_t per_line = static_cast<std::ptrdiff_t>(kAlign / sizeof(Real));
    offset_ = per_line;  // column 0 aligned, the left halo just before it
    stride_ = (offset_ + n + 1 + per_line - 1) / per_line * per_line;
    const std::size_t elements = static_cast<std::size_t>(stride_) * static_cast<std::size_t>(n + 2);
    for (Buffer* buf : {&a_[0], &a_[1], &b_[0], &b_[1]}) {
        buf->reset(static_cast<Real*>(::operator new[](elements * sizeof(Real), std::align_val_t(kAlign))));
        std::fill(buf->get(), buf->get() + elements, Real(0));
    }
    load(a_[0], a);
    load(b_[0], b);
}

template <class Real>
Real* GrayScottKernel<Real>::row(const Buffer& buf, int i) const {
    return buf.get() + static_cast<std::ptrdiff_t>(i + 1) * stride_ + offset_;
}

template <class Real>
void GrayScottKernel<Real>::load(Buffer& buf, const Grid<double>& g) {
    const int n = params_.n;
    for (int i = 0; i < n; ++i) {
        Real* dst = row(buf, i);
        for (int j = 0; j < n; ++j) dst[j] = static_cast<Real>(g(i, j));
        wrap_row(dst, n);
    }
    std::copy(row(buf, n - 1) - 1, row(buf, n - 1) + n + 1, row(buf, -1) - 1);
    std::copy(row(buf, 0) - 1, row(buf, 0) + n + 1, row(buf, n) - 1);
}

template <class Real>
Grid<double> GrayScottKernel<Real>::extract(const Buffer& buf) const {
    const int n = params_.n;
    Grid<double> g(n, n);
    for (int i = 0; i < n; ++i) {
        const Real* src = row(buf, i);
        for (int j = 0; j < n; ++j) g(i, j) = static_cast<double>(src[j]);
    }
    return g;
}

template <class Real>
Grid<double> GrayScottKernel<Real>::a() const {
    return extract(a_[current_]);
}

template <class Real>
Grid<double> GrayScottKernel<Real>::b() const {
    return extract(b_[current_]);
}

template <class Real>
void GrayScottKernel<Real>::step(int steps, int threads) {
    if (steps < 0) throw std::invalid_argument("steps is " + std::to_string(steps) + ", not >= 0");
    if (threads < 0) throw std::invalid_argument("threads is " + std::to_string(threads) + ", not >= 0");
    if (steps == 0) return;
    const int n = params_.n;
    const Rates<Real> rates{static_cast<Real>(params_.ra), static_cast<Real>(params_.rb), static_cast<Real>(params_.f),
                            static_cast<Real>(params_.f + params_.k)};
    const int first = current_;
#ifdef _OPENMP
    const int team = threads > 0 ? threads : omp_get_max_threads();
    StepBarrier sync;
#pragma omp parallel num_threads(team) if (team > 1)
#endif
    {
#ifdef _OPENMP
        sync.join(omp_get_num_threads());  // the team that runs (thread limits may shrink it)
#endif
        for (int s = 0; s < steps; ++s) {
            const int from = (first + s) & 1, to = from ^ 1;
            const Buffer &a = a_[from], &b = b_[from], &na = a_[to], &nb = b_[to];
#ifdef _OPENMP
#pragma omp for schedule(static) nowait
#endif
            for (int i = 0; i < n; ++i) {
                Real* out_a = row(na, i);
                Real* out_b = row(nb, i);
                update_row<Real>(row(a, i - 1), row(a, i), row(a, i + 1), row(b, i - 1), row(b, i), row(b, i + 1),
                                 out_a, out_b, n, rates);
                wrap_row(out_a, n);
                wrap_row(out_b, n);
                // The halo rows of the new pair: row -1 copies row n - 1, row n copies row 0.
                if (i == n - 1) {
                    std::copy(out_a - 1, out_a + n + 1, row(na, -1) - 1);
                    std::copy(out_b - 1, out_b + n + 1, row(nb, -1) - 1);
                }
                if (i == 0) {
                    std::copy(out_a - 1, out_a + n + 1, row(na, n) - 1);
                    std::copy(out_b - 1, out_b + n + 1, row(nb, n) - 1);
                }
            }
#ifdef _OPENMP
            // The new pair is complete before the next step reads it; after the
            // last step the region's own join barrier does that.
            if (s + 1 < steps) sync.arrive_and_wait();
#endif
        }
    }
#ifndef _OPENMP
    (void)threads;
#endif
    current_ = (first + steps) & 1;
    steps_ += steps;
}

template class GrayScottKernel<float>;
template class GrayScottKernel<double>;

}  // namespace sim
