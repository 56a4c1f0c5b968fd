#pragma once
// The threaded step loop of the fast stencil kernels
// (sim/gray_scott_kernels.hpp, sim/diffusion_kernel.hpp): one OpenMP team for
// a whole run of steps, the rows of each step split among its threads, a
// barrier between steps. Without OpenMP it runs on one thread.

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif
#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace sim {

// While it lives, the calling thread's SSE/AVX arithmetic flushes subnormal
// results to zero and reads subnormal inputs as zero (MXCSR's FTZ and DAZ
// bits); the old mode comes back after. Subnormal operands cost ~100 cycles
// each on x86: a float Gray-Scott run whose B decays to 1e-38 in the empty
// regions fell from 2 to 0.2 G cell-updates/s. The mode is part of IEEE
// arithmetic's specified behaviour on every x86-64 and the same on every
// thread, so results stay deterministic and independent of the thread count.
// A no-op elsewhere.
class SubnormalsFlushed {
public:
#if defined(__SSE__) || defined(__x86_64__)
    SubnormalsFlushed() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }  // FTZ 0x8000, DAZ 0x0040
    ~SubnormalsFlushed() { _mm_setcsr(saved_); }

private:
    unsigned saved_;
#endif
};

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

// Calls update_rows(s, begin, end) for s = 0 .. steps - 1 on `threads`
// OpenMP threads (0: OpenMP's default; > 0: that many, but never more than the
// CPUs the process may run on): in each step
// every thread gets one contiguous block [begin, end) of the rows 0 .. rows - 1
// (a static split; one call per block, so the kernel hoists its per-step work
// out of the row loop), and all rows of step s are done before any of step
// s + 1 starts. When a row reads only the previous step's state, the result
// therefore does not depend on the thread count.
template <class UpdateRows>
void parallel_steps(int rows, int steps, int threads, const UpdateRows& update_rows) {
    if (steps < 0) throw std::invalid_argument("steps is " + std::to_string(steps) + ", not >= 0");
    if (threads < 0) throw std::invalid_argument("threads is " + std::to_string(threads) + ", not >= 0");
    if (steps == 0) return;
#ifdef _OPENMP
    // More threads than CPUs only add waits: every step ends at a barrier, and
    // a thread that is not running holds the others there (fx-fhn-labyrinth,
    // 40,000 steps of 128^2 cells: 1.6 s on 2 threads, 6.7 s on 3, on 2 CPUs).
    // The rows' results do not depend on the count, so the team is cut to the
    // CPUs the process may run on (omp_get_num_procs follows its affinity).
    const int team = std::min(threads > 0 ? threads : omp_get_max_threads(), std::max(1, omp_get_num_procs()));
    StepBarrier sync;
#pragma omp parallel num_threads(team) if (team > 1)
    {
        // The team that runs (thread limits may shrink it).
        const long long size = omp_get_num_threads(), me = omp_get_thread_num();
        sync.join(static_cast<int>(size));
        const int begin = static_cast<int>(rows * me / size), end = static_cast<int>(rows * (me + 1) / size);
        for (int s = 0; s < steps; ++s) {
            update_rows(s, begin, end);
            // Step s is complete before step s + 1 reads it; after the last
            // step the region's own join barrier does that.
            if (s + 1 < steps) sync.arrive_and_wait();
        }
    }
#else
    (void)threads;
    for (int s = 0; s < steps; ++s) update_rows(s, 0, rows);
#endif
}

}  // namespace sim
