// A kernel rule's run on an image: sim/kernel/run.hpp.

#include "sim/kernel/run.hpp"

#include <omp.h>
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "sim/kernel/compile.hpp"
#include "sim/kernel/lanes.hpp"

namespace sim::kernel {

namespace {

// Subnormal numbers flushed to zero while it lives, in the arithmetic's
// inputs (DAZ) and results (FTZ), on this thread.
class Flush {
public:
#if defined(__SSE2__)
    Flush() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }
    ~Flush() { _mm_setcsr(saved_); }

private:
    unsigned saved_;
#else
    Flush() = default;
#endif
};

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

long long mesh_run_bytes(const MeshRule& rule, long long cells, int max_neighbors) {
    const long long number = rule.float64 ? 8 : 4;
    return static_cast<long long>(rule.chemicals) * cells * (2 * number + 4) + cells * max_neighbors * 8LL;
}

long long thread_bytes(const ImageRule& rule, int width, int height, int depth) {
    const Compiled c = compile(parse(rule.text), interface_of(rule, width, height, depth));
    return static_cast<long long>(c.registers) * lanes * 8 + static_cast<long long>(c.masks) * lanes + c.registers;
}

struct KernelRun::Impl {
    int chemicals = 1;
    bool float64 = false;
    long long cells = 0;
    Compiled program;
    std::vector<Extra> extras;
    // buffers[k][c]: chemical c's numbers in buffer k, as bytes
    std::vector<std::vector<unsigned char>> buffers[2];
    std::vector<std::vector<std::int32_t>> stamps;
    int current = 0;
    long long steps = 0;
    // A step of under threaded_step_operations (each over a chunk's lanes,
    // counted on the run's first step) runs on one thread: the team's start
    // and barrier would cost as much as they save, and far more on a
    // machine whose cores are busy (Life on a Penrose tiling, about 6,000
    // of them, 1 ms a step: 2 to 3 times slower on two threads of a busy
    // 2-core machine). The bits are the same on any number of threads.
    static constexpr long long threaded_step_operations = 20000;
    bool one_thread_enough = false, counted = false;
    std::vector<std::unique_ptr<Lanes>> threads;

    double get(int k, int c, long long i) const {
        const unsigned char* b = buffers[k][static_cast<std::size_t>(c)].data();
        if (float64) {
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
        const int buffers_of_chemicals = 2 * chemicals;
        for (const BufferView& v : program.buffers) {
            if (v.parameter >= buffers_of_chemicals) {
                const Extra& e = extras[static_cast<std::size_t>(v.parameter - buffers_of_chemicals)];
                const void* data = e.kind == Extra::Kind::ints ? static_cast<const void*>(e.ints.data())
                                                               : static_cast<const void*>(e.floats.data());
                const auto count = static_cast<long long>(e.kind == Extra::Kind::ints ? e.ints.size() : e.floats.size());
                launch.data.push_back(data);
                launch.out.push_back(nullptr);
                launch.elements.push_back(count / v.width);
                launch.stamps.push_back(nullptr);
                continue;
            }
            const int c = v.parameter % chemicals;
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
            // Ready builds kernels with -cl-denorms-are-zero, and pocl
            // flushes subnormal numbers to zero, in and out: so does the run.
            const Flush flush;
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
        for (int c = 0; c < chemicals; ++c)
            for (long long i = 0; i < cells; ++i)
                if (!std::isfinite(get(1 - current, c, i)))
                    throw KernelError("step " + std::to_string(steps + 1) + ": chemical " +
                                      std::string(1, static_cast<char>('a' + c)) + " is no longer finite at " +
                                      cell_name(i) + ": the kernel went unstable");
        current = 1 - current;
        ++steps;
    }

    std::function<std::string(long long)> cell_name;
};

KernelRun::KernelRun(const std::string& text, int chemicals, bool float64, long long cells, const long long global[3],
                     std::vector<Extra> extras, const std::vector<std::vector<double>>& start, long long trip_budget)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    if (cells < 1 || cells > max_kernel_cells) throw std::invalid_argument("a kernel runs over 1 to 2^31 - 1 cells");
    if (static_cast<int>(start.size()) != chemicals) throw std::invalid_argument("a start a chemical");
    m.chemicals = chemicals;
    m.float64 = float64;
    m.cells = cells;
    m.extras = std::move(extras);
    Interface iface;
    for (int k = 0; k < 3; ++k) iface.global[k] = global[k];
    iface.trip_budget = trip_budget;
    const Scalar s = float64 ? Scalar::f64 : Scalar::f32;
    for (int io = 0; io < 2; ++io)
        for (int c = 0; c < chemicals; ++c)
            iface.parameters.push_back(Binding{io == 0 ? Binding::Kind::input : Binding::Kind::output, s, 0});
    for (const Extra& e : m.extras)
        iface.parameters.push_back(e.kind == Extra::Kind::value ? Binding{Binding::Kind::value, Scalar::i32, e.value}
                                   : e.kind == Extra::Kind::ints ? Binding{Binding::Kind::input, Scalar::i32, 0}
                                                                 : Binding{Binding::Kind::input, Scalar::f32, 0});
    m.program = compile(parse(text), iface);
    const long long number = float64 ? 8 : 4;
    for (int k = 0; k < 2; ++k) m.buffers[k].resize(static_cast<std::size_t>(chemicals));
    m.stamps.resize(static_cast<std::size_t>(chemicals));
    for (int c = 0; c < chemicals; ++c) {
        const std::vector<double>& g = start[static_cast<std::size_t>(c)];
        if (static_cast<long long>(g.size()) != cells) throw std::invalid_argument("a start of the run's size");
        auto& b0 = m.buffers[0][static_cast<std::size_t>(c)];
        b0.assign(static_cast<std::size_t>(cells * number), 0);
        m.buffers[1][static_cast<std::size_t>(c)].assign(static_cast<std::size_t>(cells * number), 0);
        m.stamps[static_cast<std::size_t>(c)].assign(static_cast<std::size_t>(cells), -1);
        for (long long i = 0; i < cells; ++i) {
            const double v = g[static_cast<std::size_t>(i)];
            if (float64) std::memcpy(b0.data() + i * 8, &v, 8);
            else {
                const float f = static_cast<float>(v);
                std::memcpy(b0.data() + i * 4, &f, 4);
            }
        }
    }
    m.cell_name = [](long long i) { return "cell " + std::to_string(i); };
    m.make_chunks();
}

KernelRun::~KernelRun() = default;
KernelRun::KernelRun(KernelRun&&) noexcept = default;
KernelRun& KernelRun::operator=(KernelRun&&) noexcept = default;

void KernelRun::step(int steps, int threads) {
    Impl& m = *impl_;
    const int team = std::max(1, std::min(threads > 0 ? threads : omp_get_max_threads(), std::max(1, omp_get_num_procs())));
    while (static_cast<int>(m.threads.size()) < team) m.threads.push_back(std::make_unique<Lanes>(m.program));
    for (int s = 0; s < steps; ++s) {
        if (!m.counted && team > 1) {
            const long long before = m.threads[0]->executed();
            m.one_step(1);
            m.counted = true;
            m.one_thread_enough = m.threads[0]->executed() - before < Impl::threaded_step_operations;
            continue;
        }
        m.one_step(m.one_thread_enough ? 1 : team);
    }
}

std::vector<double> KernelRun::values(int chemical) const {
    const Impl& m = *impl_;
    std::vector<double> out(static_cast<std::size_t>(m.cells));
    for (long long k = 0; k < m.cells; ++k) out[static_cast<std::size_t>(k)] = m.get(m.current, chemical, k);
    return out;
}

long long KernelRun::steps() const { return impl_->steps; }
void KernelRun::name_cells(std::function<std::string(long long)> name) { impl_->cell_name = std::move(name); }
int KernelRun::operations() const { return impl_->program.operations; }

namespace {

std::vector<std::vector<double>> numbers_of(const std::vector<Grid<double>>& grids) {
    std::vector<std::vector<double>> out;
    for (const Grid<double>& g : grids) out.emplace_back(g.cells().begin(), g.cells().end());
    return out;
}

}  // namespace

ImageRun::ImageRun(const ImageRule& rule, int width, int height, int depth, const std::vector<Grid<double>>& start)
    : width_(width), height_(height), depth_(depth) {
    if (width < 1 || height < 1 || depth < 1) throw std::invalid_argument("a kernel's grid is at least 1 x 1 x 1");
    const long long cells = static_cast<long long>(width) * height * depth;
    if (cells > max_kernel_cells) throw std::invalid_argument("a kernel's grid has at most 2^31 - 1 cells");
    const Interface iface = interface_of(rule, width, height, depth);
    run_ = std::make_unique<KernelRun>(rule.text, rule.chemicals, rule.float64, cells, iface.global, std::vector<Extra>{},
                                       numbers_of(start), rule.trip_budget);
    // a cell named by its place in the grid
    run_->name_cells([width, height](long long i) {
        return "cell " + std::to_string(i % width) + ", " + std::to_string(i / width % height) + ", " +
               std::to_string(i / (static_cast<long long>(width) * height));
    });
}

ImageRun::~ImageRun() = default;
ImageRun::ImageRun(ImageRun&&) noexcept = default;
ImageRun& ImageRun::operator=(ImageRun&&) noexcept = default;

void ImageRun::step(int steps, int threads) { run_->step(steps, threads); }

Grid<double> ImageRun::chemical(int i) const {
    const std::vector<double> v = run_->values(i);
    Grid<double> g(height_ * depth_, width_);
    std::copy(v.begin(), v.end(), g.data());
    return g;
}

long long ImageRun::steps() const { return run_->steps(); }
int ImageRun::operations() const { return run_->operations(); }

std::string mesh_formula_kernel(const std::string& formula, int chemicals, bool float64,
                                const std::vector<std::pair<std::string, double>>& parameters) {
    const std::string type = float64 ? "double" : "float", suffix = float64 ? "" : "f", indent = "    ";
    auto name = [](int c) { return std::string(1, static_cast<char>('a' + c)); };
    std::string k;
    if (float64)
        k += "#ifdef cl_khr_fp64\n    #pragma OPENCL EXTENSION cl_khr_fp64 : enable\n#elif defined(cl_amd_fp64)\n"
             "    #pragma OPENCL EXTENSION cl_amd_fp64 : enable\n#else\n    #error \"Double precision floating point "
             "not supported on this OpenCL device. Choose another or contact the Ready team.\"\n#endif\n\n";
    k += "kernel void rd_compute(";
    for (int c = 0; c < chemicals; ++c) k += "global " + type + " *" + name(c) + "_in,";
    for (int c = 0; c < chemicals; ++c) k += "global " + type + " *" + name(c) + "_out,";
    k += "global int* neighbor_indices,global float* neighbor_weights,const int max_neighbors)\n{\n";
    k += indent + "const int index_x = get_global_id(0);\n";
    for (int c = 0; c < chemicals; ++c) k += indent + type + " " + name(c) + " = " + name(c) + "_in[index_x];\n";
    k += "\n" + indent + "// compute the Laplacians\n";
    for (int c = 0; c < chemicals; ++c) k += indent + type + " laplacian_" + name(c) + " = -" + name(c) + ";\n";
    k += indent + "int _offset = index_x * max_neighbors;\n";
    k += indent + "for(int _i=0;_i<max_neighbors;_i++)\n" + indent + "{\n";
    for (int c = 0; c < chemicals; ++c)
        k += indent + indent + "laplacian_" + name(c) + " += " + name(c) +
             "_in[neighbor_indices[_offset+_i]] * neighbor_weights[_offset+_i];\n";
    k += indent + "}\n";
    for (int c = 0; c < chemicals; ++c) k += indent + "laplacian_" + name(c) + " *= 4.0" + suffix + ";\n";
    k += "\n" + indent + "// parameters:\n";
    for (const auto& [pname, value] : parameters) {
        char text[400];
        std::snprintf(text, sizeof text, "%.6f", value);  // Ready's `fixed << setprecision(6)`
        k += indent + type + " " + pname + " = " + text + suffix + ";\n";
    }
    for (int c = 0; c < chemicals; ++c) k += indent + type + " delta_" + name(c) + " = 0.0" + suffix + ";\n";
    k += "\n" + indent + "// the formula:\n" + formula + "\n";
    k += indent + "// forward-Euler update step:\n";
    for (int c = 0; c < chemicals; ++c)
        k += indent + name(c) + "_out[index_x] = " + name(c) + " + timestep * delta_" + name(c) + ";\n";
    k += "}\n";
    return k;
}

namespace {

// A mesh kernel's parameters: the chemicals' buffers, then the neighbour
// indices, their weights and max_neighbors.
std::vector<Extra> mesh_extras(const std::vector<int>& indices, const std::vector<float>& weights, int max_neighbors) {
    std::vector<Extra> extras(3);
    extras[0].kind = Extra::Kind::ints;
    extras[0].ints.assign(indices.begin(), indices.end());
    extras[1].kind = Extra::Kind::floats;
    extras[1].floats = weights;
    extras[2].kind = Extra::Kind::value;
    extras[2].value = max_neighbors;
    return extras;
}

}  // namespace

int mesh_kernel_operations(const MeshRule& rule, long long cells, int max_neighbors) {
    Interface iface;
    iface.global[0] = cells;
    iface.trip_budget = rule.trip_budget;
    const Scalar s = rule.float64 ? Scalar::f64 : Scalar::f32;
    for (int io = 0; io < 2; ++io)
        for (int c = 0; c < rule.chemicals; ++c)
            iface.parameters.push_back(Binding{io == 0 ? Binding::Kind::input : Binding::Kind::output, s, 0});
    iface.parameters.push_back(Binding{Binding::Kind::input, Scalar::i32, 0});
    iface.parameters.push_back(Binding{Binding::Kind::input, Scalar::f32, 0});
    iface.parameters.push_back(Binding{Binding::Kind::value, Scalar::i32, max_neighbors});
    return compile(parse(rule.text), iface).operations;
}

MeshRun::MeshRun(const MeshRule& rule, long long cells, int max_neighbors, const std::vector<int>& indices,
                 const std::vector<float>& weights, const std::vector<std::vector<double>>& start) {
    if (max_neighbors < 0 || static_cast<long long>(indices.size()) != cells * max_neighbors ||
        indices.size() != weights.size())
        throw std::invalid_argument("a mesh run's neighbour lists are cells x max_neighbors");
    const long long global[3] = {cells, 1, 1};
    run_ = std::make_unique<KernelRun>(rule.text, rule.chemicals, rule.float64, cells, global,
                                       mesh_extras(indices, weights, max_neighbors), start, rule.trip_budget);
}

}  // namespace sim::kernel
