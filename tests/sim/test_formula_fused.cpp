// Chains of a compiled formula (sim/formula/chain_kernels.hpp): operations fused
// into one pass round as each does alone (against the same arithmetic in
// plain C++, term by term), on every instruction set the processor has,
// and Ready's Gray-Scott fuses as expected.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "grid_bits.hpp"
#include "sim/formula/run.hpp"
#include "sim/formula/chain_kernels.hpp"
#include "sim/formula/program.hpp"
#include "sim/random.hpp"

using sim::Grid;
using namespace sim::formula;

namespace {

// What runs a chain: the vector code of an instruction set, or the
// chain's machine code (sim/formula/chain_jit.hpp).
struct Engine {
    fused::Isa isa;
    bool jit;
};

// The instruction sets this processor runs, plain C++ first, then the
// machine code where this build and processor make it.
std::vector<Engine> instruction_sets() {
    std::vector<Engine> all{{fused::Isa::plain, false}};
    if (fused::best_isa() >= fused::Isa::avx2) all.push_back({fused::Isa::avx2, false});
    if (fused::best_isa() >= fused::Isa::avx512) all.push_back({fused::Isa::avx512, false});
    if (fused::jit_available()) all.push_back({fused::best_isa(), true});
    return all;
}

void use(const Engine& e) {
    fused::use_isa(e.isa);
    fused::use_jit(e.jit);
}

// Puts back the instruction set and machine code in use when it goes.
struct KeepIsa {
    fused::Isa saved = fused::isa();
    bool jit = fused::jit_in_use();
    ~KeepIsa() {
        fused::use_isa(saved);
        fused::use_jit(jit);
    }
};

Rule two_chemicals(const std::string& code, bool opencl = false) {
    Rule r;
    r.fused_multiply_add = opencl;
    r.parameters = {{"timestep", 1.0}};
    r.code = code;
    r.ready_edges = false;  // a torus at any size
    r.block_x = 1;
    return r;
}

// Values from low to high, not a pattern a wrong lane would hide in.
Grid<double> start(int width, int height, std::uint64_t seed, double low = 0.1, double high = 1.6) {
    sim::Random rng(seed);
    Grid<double> g(height, width);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) g(y, x) = static_cast<float>(rng.uniform(low, high));
    return g;
}

// The kinds of operation the formula's chains use.
std::set<fused::Kind> kinds_of(const Rule& rule) {
    const Program program = compile(rule);
    std::set<fused::Kind> kinds;
    for (const Chain& chain : program.chains)
        for (const fused::Micro<float>& m : fused::plan_float(program, chain).code) kinds.insert(m.kind);
    return kinds;
}

// One step of `code` in float on a torus, against `reference` (the new a
// and b of a cell from a, b and a's east and west neighbours), on every
// instruction set.
void check_one_step(const std::string& code,
                    const std::function<void(float a, float b, float ae, float aw, float& na, float& nb)>& reference,
                    bool opencl = false) {
    constexpr int width = 70, height = 9;  // a row is not a whole number of vectors
    const Grid<double> a = start(width, height, 3), b = start(width, height, 4);
    Grid<double> want_a(height, width), want_b(height, width);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float na = 0, nb = 0;
            reference(static_cast<float>(a(y, x)), static_cast<float>(b(y, x)),
                      static_cast<float>(a(y, (x + 1) % width)), static_cast<float>(a(y, (x + width - 1) % width)), na,
                      nb);
            want_a(y, x) = na;
            want_b(y, x) = nb;
        }
    KeepIsa keep;
    for (const Engine& e : instruction_sets()) {
        INFO("instruction set " << static_cast<int>(e.isa) << (e.jit ? ", machine code" : ""));
        use(e);
        Run run(two_chemicals(code, opencl), width, height, {a, b});
        run.step(1, 1);
        CHECK(same_bits(run.chemical(0), want_a));
        CHECK(same_bits(run.chemical(1), want_b));
    }
}

}  // namespace

TEST_CASE("a chain rounds each operation as it does alone, on every instruction set", "[formula]") {
    const std::string first = "delta_a = ((a_e - a) * b + (2.0f - a_w) * 0.5f) / 4.0f - (3.0f - a*b);\n"
                              "delta_b = 1.5f - (b*3.0f - a_e) * (0.25f - b) / 2.0f;";
    check_one_step(first, [](float a, float b, float ae, float aw, float& na, float& nb) {
        const float da = ((ae - a) * b + (2.0f - aw) * 0.5f) / 4.0f - (3.0f - a * b);
        const float db = 1.5f - (b * 3.0f - ae) * (0.25f - b) / 2.0f;
        na = a + da;
        nb = b + db;
    });
    const std::string second = "delta_a = (a_w - b) * (b - a) - (a_e + a) * 0.5f + b / 8.0f;\n"
                               "delta_b = (b - (a - 1.0f) / 3.0f) * 2.0f - (1.0f - b) * (a_w + b) - (0.5f - a_e * b);";
    check_one_step(second, [](float a, float b, float ae, float aw, float& na, float& nb) {
        const float da = (aw - b) * (b - a) - (ae + a) * 0.5f + b / 8.0f;
        const float db = (b - (a - 1.0f) / 3.0f) * 2.0f - (1.0f - b) * (aw + b) - (0.5f - ae * b);
        na = a + da;
        nb = b + db;
    });
    // Between them the two formulas use most kinds of operation.
    std::set<fused::Kind> used = kinds_of(two_chemicals(first));
    for (fused::Kind k : kinds_of(two_chemicals(second))) used.insert(k);
    for (fused::Kind k : {fused::Kind::acc_set_row, fused::Kind::acc_sub_row, fused::Kind::acc_rsub_row,
                          fused::Kind::acc_rsub_k, fused::Kind::acc_mul_row, fused::Kind::acc_mul_k,
                          fused::Kind::acc_div_k, fused::Kind::acc_add_row, fused::Kind::aux_set_k,
                          fused::Kind::aux_set_row, fused::Kind::aux_sub_row, fused::Kind::aux_mul_k,
                          fused::Kind::aux_mul_row, fused::Kind::aa_add, fused::Kind::aa_sub, fused::Kind::end}) {
        INFO("kind " << static_cast<int>(k));
        CHECK(used.count(k) == 1);
    }
}

TEST_CASE("Ready's Gray-Scott fuses into three chains, the same bits on every instruction set", "[formula]") {
    Rule rule = two_chemicals("delta_a = D_a * laplacian_a - a*b*b + F*(1.0f-a);\n"
                              "delta_b = D_b * laplacian_b + a*b*b - (F+K)*b;");
    rule.parameters = {{"timestep", 1.0}, {"D_a", 0.082}, {"D_b", 0.041}, {"K", 0.06}, {"F", 0.035}};
    const Program program = compile(rule);
    // a*b*b, read twice, is a chain of its own; each chemical's update one
    // more, its F*(1-a) or (F+K)*b in the second accumulator.
    CHECK(program.chains.size() == 3);
    CHECK(program.code.size() == 3);
    CHECK(program.operations == 15);
    const Grid<double> a = start(64, 48, 5, 0.4, 1.0), b = start(64, 48, 6, 0.0, 0.4);
    KeepIsa keep;
    std::vector<Grid<double>> results;
    for (const Engine& e : instruction_sets()) {
        use(e);
        Run run(rule, 64, 48, {a, b});
        run.step(50, 2);
        results.push_back(run.chemical(1));
    }
    for (std::size_t i = 1; i < results.size(); ++i) CHECK(same_bits(results[i], results[0]));
    CHECK_THROWS_AS(fused::use_isa(static_cast<fused::Isa>(static_cast<int>(fused::best_isa()) + 1)),
                    std::invalid_argument);
}

TEST_CASE("fused multiply-adds in a chain round once, as clang's, on every instruction set", "[formula]") {
    // Ready's OpenCL arithmetic: the left product of a sum first, then a
    // product the sum so far meets; negated products and addends.
    const std::string code = "delta_a = b*a_e + (a_w - a)*0.5f - a*b;\n"
                             "delta_b = 2.0f*b - a_w + (a - 1.0f)*(b + a_e) - 0.5f;";
    check_one_step(
        code,
        [](float a, float b, float ae, float aw, float& na, float& nb) {
            const float da = std::fma(-a, b, std::fma(b, ae, (aw - a) * 0.5f));
            const float db = std::fma(a - 1.0f, b + ae, std::fma(2.0f, b, -aw)) - 0.5f;
            na = a + da;  // timestep 1: fma(1, delta, a) is a + delta
            nb = b + db;
        },
        true);
    const std::string more = "delta_a = 0.5f - (a_e + b)*(a - 0.25f);\n"
                             "delta_b = (b*a - a_w)*3.0f + b*0.125f;";
    check_one_step(
        more,
        [](float a, float b, float ae, float aw, float& na, float& nb) {
            const float da = std::fma(-(ae + b), a - 0.25f, 0.5f);
            const float db = std::fma(std::fma(b, a, -aw), 3.0f, b * 0.125f);
            na = a + da;
            nb = b + db;
        },
        true);
    // The fused multiply-adds run inside chains.
    std::set<fused::Kind> used = kinds_of(two_chemicals(code, true));
    for (fused::Kind k : kinds_of(two_chemicals(more, true))) used.insert(k);
    int fma_kinds = 0;
    for (fused::Kind k : {fused::Kind::acc_fma_aux_row, fused::Kind::acc_fma_aux_k, fused::Kind::acc_fma_acc_aux_row,
                          fused::Kind::acc_fms_acc_aux_row, fused::Kind::acc_fma_acc_aux_k,
                          fused::Kind::acc_fma_acc_row_aux, fused::Kind::acc_fma_acc_k_aux})
        fma_kinds += static_cast<int>(used.count(k));
    CHECK(fma_kinds >= 3);
}

TEST_CASE("Ready's Gray-Scott in Ready's OpenCL arithmetic fuses into chains too", "[formula]") {
    Rule rule = two_chemicals("delta_a = D_a * laplacian_a - a*b*b + F*(1.0f-a);\n"
                              "delta_b = D_b * laplacian_b + a*b*b - (F+K)*b;",
                              true);
    rule.parameters = {{"timestep", 1.0}, {"D_a", 0.082}, {"D_b", 0.041}, {"K", 0.06}, {"F", 0.035}};
    const Program program = compile(rule);
    int loose = 0;
    for (const Instr& in : program.code) loose += in.op == Op::fma;
    CHECK(loose == 0);
    CHECK(program.code.size() <= 4);
}

namespace {

// Random plans over every kind of operation, run on rows of `n` lanes by
// `e` and by plain C++ one lane at a time; returns whether they agree to
// the bit (and on the lanes found not finite).
template <class Real>
bool plans_agree(const Engine& e, int n, std::uint64_t seed, int plans) {
    sim::Random rng(seed);
    constexpr int rows = 6;
    std::vector<std::vector<Real>> data(rows, std::vector<Real>(static_cast<std::size_t>(n)));
    std::vector<const Real*> view(rows);
    bool all = true;
    for (int p = 0; p < plans; ++p) {
        for (int r = 0; r < rows; ++r) {
            for (Real& v : data[static_cast<std::size_t>(r)]) v = static_cast<Real>(rng.uniform(-1.6, 1.6));
            view[static_cast<std::size_t>(r)] = data[static_cast<std::size_t>(r)].data();
        }
        if (p % 7 == 3) data[2][static_cast<std::size_t>(p) % static_cast<std::size_t>(n)] = Real(1) / Real(0);
        fused::Plan<Real> plan;
        // acc, aux and g set first, as a compiled chain sets each before
        // reading it; then every kind once at least, in order in the
        // first plan, then at random.
        for (fused::Kind set : {fused::Kind::acc_set_row, fused::Kind::aux_set_row, fused::Kind::g_set_row})
            plan.code.push_back({set, static_cast<int>(rng.uniform(0, rows - 1e-9)), Real(0)});
        for (int i = 0; i < 40; ++i) {
            const int kind = p == 0 ? i % (fused::kinds - 1) : static_cast<int>(rng.uniform(0, fused::kinds - 1 - 1e-9));
            Real k = static_cast<Real>(rng.uniform(0.25, 2.0));
            if (rng.uniform(0, 1) < 0.5) k = -k;
            plan.code.push_back({static_cast<fused::Kind>(kind), static_cast<int>(rng.uniform(0, rows - 1e-9)), k});
        }
        plan.code.push_back({fused::Kind::end, -1, 0});
        plan.machine = fused::compile_chain(plan);
        std::vector<Real> want(static_cast<std::size_t>(n)), got(static_cast<std::size_t>(n));
        KeepIsa keep;
        use({fused::Isa::plain, false});
        const bool want_bad = fused::run(plan, view.data(), want.data(), n, true);
        use(e);
        const bool got_bad = fused::run(plan, view.data(), got.data(), n, true);
        // The same bits, or both NaN (which NaN an operation on two of them
        // keeps is the instruction's choice of operand order).
        for (std::size_t i = 0; i < want.size(); ++i)
            all = all && (std::memcmp(&want[i], &got[i], sizeof(Real)) == 0 || (std::isnan(want[i]) && std::isnan(got[i])));
        all = all && want_bad == got_bad;
    }
    return all;
}

}  // namespace

TEST_CASE("every kind of chain operation gives the plain code's bits on every instruction set", "[formula]") {
    // Rows of 77 lanes: blocks of four vectors, single vectors, then lanes
    // one at a time; a row with an infinity in some plans.
    for (const Engine& e : instruction_sets()) {
        INFO("instruction set " << static_cast<int>(e.isa) << (e.jit ? ", machine code" : ""));
        CHECK(plans_agree<float>(e, 77, 11, 60));
        CHECK(plans_agree<double>(e, 77, 12, 60));
    }
    // The machine code is what runs by default where it can.
    CHECK(fused::jit_in_use() == fused::jit_available());
#if defined(__x86_64__) && !defined(__clang__)
    CHECK(fused::jit_available() == (fused::best_isa() >= fused::Isa::avx2));
#endif
}
