// A kernel rule's run on an image: sim/kernel/run.hpp.

#include "sim/kernel/run.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "sim/kernel/compile.hpp"
#include "sim/kernel/lanes.hpp"

namespace sim::kernel {

namespace {

long long global_of(int cells, int block) { return std::max(1, cells / block); }

Interface interface_of(const ImageRule& rule, int width, int height, int depth) {
    Interface iface;
    iface.global[0] = global_of(width, rule.block[0]);
    iface.global[1] = global_of(height, rule.block[1]);
    iface.global[2] = global_of(depth, rule.block[2]);
    iface.trip_budget = rule.trip_budget;
    const Scalar s = rule.float64 ? Scalar::f64 : Scalar::f32;
    for (int io = 0; io < 2; ++io)
        for (int c = 0; c < rule.chemicals; ++c)
            iface.parameters.push_back(Binding{io == 0 ? Binding::Kind::input : Binding::Kind::output, s, 0});
    return iface;
}

}  // namespace

long long run_bytes(const ImageRule& rule, long long cells) {
    const long long number = rule.float64 ? 8 : 4;
    return static_cast<long long>(rule.chemicals) * cells * (2 * number + 4);
}

long long thread_bytes(const ImageRule& rule, int width, int height, int depth) {
    const Compiled c = compile(parse(rule.text), interface_of(rule, width, height, depth));
    return static_cast<long long>(c.registers) * lanes * 8 + static_cast<long long>(c.masks) * lanes + c.registers;
}

struct ImageRun::Impl {
    ImageRule rule;
    int width = 0, height = 0, depth = 0;
    long long cells = 0;
    Compiled program;
    // buffers[k][c]: chemical c's numbers in buffer k, as bytes
    std::vector<std::vector<unsigned char>> buffers[2];
    std::vector<std::vector<std::int32_t>> stamps;
    int current = 0;
    long long steps = 0;
    std::vector<std::unique_ptr<Lanes>> threads;

    double get(int k, int c, long long i) const {
        const unsigned char* b = buffers[k][static_cast<std::size_t>(c)].data();
        if (rule.float64) {
            double v;
            std::memcpy(&v, b + i * 8, 8);
            return v;
        }
        float v;
        std::memcpy(&v, b + i * 4, 4);
        return v;
    }

    // The chunks of work items: whole rows of x when a chunk holds one or
    // more, so that the rows' ids are uniform in a chunk.
    struct Chunk {
        long long first;
        int count;
    };
    std::vector<Chunk> chunks;

    void make_chunks() {
        const long long gx = program.global[0], rows = program.global[1] * program.global[2];
        if (gx >= lanes) {
            for (long long r = 0; r < rows; ++r)
                for (long long x = 0; x < gx; x += lanes)
                    chunks.push_back({r * gx + x, static_cast<int>(std::min<long long>(lanes, gx - x))});
        } else {
            const long long per = lanes / gx;
            for (long long r = 0; r < rows; r += per)
                chunks.push_back({r * gx, static_cast<int>(std::min(per, rows - r) * gx)});
        }
    }

    std::string where(long long item) const {
        const long long gx = program.global[0], gy = program.global[1];
        return "work item (" + std::to_string(item % gx) + ", " + std::to_string(item / gx % gy) + ", " +
               std::to_string(item / (gx * gy)) + ")";
    }

    void one_step(int team) {
        Launch launch;
        for (const BufferView& v : program.buffers) {
            const int c = v.parameter % rule.chemicals;
            const int k = v.output ? 1 - current : current;
            unsigned char* data = buffers[k][static_cast<std::size_t>(c)].data();
            launch.data.push_back(data);
            launch.out.push_back(v.output ? data : nullptr);
            launch.elements.push_back(cells / v.width);
            std::int32_t* s = nullptr;
            if (v.output) {
                auto& st = stamps[static_cast<std::size_t>(c)];
                std::fill(st.begin(), st.end(), -1);
                s = st.data();
            }
            launch.stamps.push_back(s);
        }
        const auto n = static_cast<long long>(chunks.size());
        std::vector<Failure> failures(static_cast<std::size_t>(team));
        std::vector<long long> failed_chunk(static_cast<std::size_t>(team), n);
#pragma omp parallel num_threads(team) if (team > 1)
        {
            const int me = omp_get_thread_num();
            Lanes& lanes_of = *threads[static_cast<std::size_t>(me)];
#pragma omp for schedule(static)
            for (long long i = 0; i < n; ++i) {
                if (failed_chunk[static_cast<std::size_t>(me)] < n) continue;
                const Chunk& ch = chunks[static_cast<std::size_t>(i)];
                if (!lanes_of.run(launch, ch.first, ch.count, failures[static_cast<std::size_t>(me)]))
                    failed_chunk[static_cast<std::size_t>(me)] = i;
            }
        }
        const auto first = std::min_element(failed_chunk.begin(), failed_chunk.end());
        if (*first < n) {
            const Failure& f = failures[static_cast<std::size_t>(first - failed_chunk.begin())];
            throw KernelError("kernel line " + std::to_string(f.line) + ", step " + std::to_string(steps + 1) + ", " +
                              where(f.item) + ": " + f.what);
        }
        // a number no longer finite stops the run before it is drawn
        for (int c = 0; c < rule.chemicals; ++c) {
            const unsigned char* b = buffers[1 - current][static_cast<std::size_t>(c)].data();
            for (long long i = 0; i < cells; ++i) {
                bool finite;
                if (rule.float64) {
                    double v;
                    std::memcpy(&v, b + i * 8, 8);
                    finite = std::isfinite(v);
                } else {
                    float v;
                    std::memcpy(&v, b + i * 4, 4);
                    finite = std::isfinite(v);
                }
                if (!finite)
                    throw KernelError("step " + std::to_string(steps + 1) + ": chemical " + std::string(1, static_cast<char>('a' + c)) +
                                      " is no longer finite at cell " + std::to_string(i % width) + ", " +
                                      std::to_string(i / width % height) + ", " + std::to_string(i / (static_cast<long long>(width) * height)) +
                                      ": the kernel went unstable");
            }
        }
        current = 1 - current;
        ++steps;
    }
};

ImageRun::ImageRun(const ImageRule& rule, int width, int height, int depth, const std::vector<Grid<double>>& start)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    if (width < 1 || height < 1 || depth < 1) throw std::invalid_argument("a kernel's grid is at least 1 x 1 x 1");
    m.cells = static_cast<long long>(width) * height * depth;
    if (m.cells > max_kernel_cells) throw std::invalid_argument("a kernel's grid has at most 2^31 - 1 cells");
    if (static_cast<int>(start.size()) != rule.chemicals) throw std::invalid_argument("a start grid a chemical");
    m.rule = rule;
    m.width = width, m.height = height, m.depth = depth;
    m.program = compile(parse(rule.text), interface_of(rule, width, height, depth));
    const long long number = rule.float64 ? 8 : 4;
    for (int k = 0; k < 2; ++k) m.buffers[k].resize(static_cast<std::size_t>(rule.chemicals));
    m.stamps.resize(static_cast<std::size_t>(rule.chemicals));
    for (int c = 0; c < rule.chemicals; ++c) {
        const Grid<double>& g = start[static_cast<std::size_t>(c)];
        if (static_cast<long long>(g.size()) != m.cells) throw std::invalid_argument("a start grid of the run's size");
        auto& b0 = m.buffers[0][static_cast<std::size_t>(c)];
        b0.assign(static_cast<std::size_t>(m.cells * number), 0);
        m.buffers[1][static_cast<std::size_t>(c)].assign(static_cast<std::size_t>(m.cells * number), 0);
        m.stamps[static_cast<std::size_t>(c)].assign(static_cast<std::size_t>(m.cells), -1);
        for (long long i = 0; i < m.cells; ++i) {
            const double v = g.data()[i];
            if (rule.float64) std::memcpy(b0.data() + i * 8, &v, 8);
            else {
                const float f = static_cast<float>(v);
                std::memcpy(b0.data() + i * 4, &f, 4);
            }
        }
    }
    m.make_chunks();
}

ImageRun::~ImageRun() = default;
ImageRun::ImageRun(ImageRun&&) noexcept = default;
ImageRun& ImageRun::operator=(ImageRun&&) noexcept = default;

void ImageRun::step(int steps, int threads) {
    Impl& m = *impl_;
    const int team = std::max(1, std::min(threads > 0 ? threads : omp_get_max_threads(), std::max(1, omp_get_num_procs())));
    while (static_cast<int>(m.threads.size()) < team) m.threads.push_back(std::make_unique<Lanes>(m.program));
    for (int s = 0; s < steps; ++s) m.one_step(team);
}

Grid<double> ImageRun::chemical(int i) const {
    const Impl& m = *impl_;
    Grid<double> g(m.height * m.depth, m.width);
    for (long long k = 0; k < m.cells; ++k) g.data()[k] = m.get(m.current, i, k);
    return g;
}

long long ImageRun::steps() const { return impl_->steps; }
int ImageRun::operations() const { return impl_->program.operations; }

}  // namespace sim::kernel
